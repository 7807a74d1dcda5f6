# The crack faces of the last frame of a shard run over its parts, as a picture, with ParaView's
# Python (Debian: apt-get install paraview xvfb):
#   xvfb-run -a pvpython tools/paraview_cracks.py OUTDIR     -> OUTDIR/cracks_paraview.png
# A starting point for scripting ParaView on shard's frames (docs/outputs.md, "ParaView").
import sys
from paraview.simple import *

run = sys.argv[1]
frames = PVDReader(FileName=run + "/frames.pvd")
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = frames.TimestepValues[-1]          # the last frame
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1200, 600]
body = Show(frames, view)
ColorBy(body, ("CELLS", "part"))
cracks = Threshold(Input=frames, Scalars=["POINTS", "crack_face"])
cracks.LowerThreshold, cracks.UpperThreshold = 0.5, 1.0   # ParaView 5.10+
cracks.AllScalars = 0                                     # a cell with any crack-face node
shown = Show(cracks, view)
ColorBy(shown, None)
shown.AmbientColor = shown.DiffuseColor = [1, 0.8, 0]
view.InteractionMode = "2D"
ResetCamera(view)
SaveScreenshot(run + "/cracks_paraview.png", view, ImageResolution=[1200, 600])
print("wrote", run + "/cracks_paraview.png")

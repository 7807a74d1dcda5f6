# The crushed end of the wedge at one time: the plies coloured by their in-plane shear damage d4
# (the gaps between them are the interfaces that opened), the debris particles in black. With ParaView's
# Python (Debian: apt-get install paraview xvfb):
#   xvfb-run -a pvpython render_damage.py OUTDIR TIME_MS PICTURE.png [HALF_HEIGHT_MM [CENTRE_X_MM]]
import sys
from paraview.simple import *

run, time_ms, picture = sys.argv[1], float(sys.argv[2]), sys.argv[3]
half = 1e-3 * float(sys.argv[4]) if len(sys.argv) > 4 else 3.2e-3   # half the height shown (m)
centre = 1e-3 * float(sys.argv[5]) if len(sys.argv) > 5 else 2.7e-3  # x at the middle of the picture (m)
frames = PVDReader(FileName=run + "/frames.pvd")
debris = PVDReader(FileName=run + "/particles_plate_particles.pvd")
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = min(frames.TimestepValues, key=lambda t: abs(t - 1e-3 * time_ms))
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [900, 900]
view.OrientationAxesVisibility = 0

plate = Threshold(Input=frames, Scalars=["CELLS", "part"])
plate.LowerThreshold, plate.UpperThreshold = -0.5, 0.5      # part 0: the plate (ParaView 5.10+)
shown = Show(plate, view)
ColorBy(shown, ("CELLS", "d4"))
lut = GetColorTransferFunction("d4")
lut.ApplyPreset("Cool to Warm", True)
lut.RescaleTransferFunction(0.0, 0.87)                     # d4_max of the paper's table 2
shown.SetScalarBarVisibility(view, True)

dots = Show(debris, view)
dots.ColorArrayName = ["POINTS", ""]
dots.SetRepresentationType("Points")
dots.PointSize = 5.0
dots.RenderPointsAsSpheres = 1
dots.AmbientColor = dots.DiffuseColor = [0.0, 0.0, 0.0]

view.InteractionMode = "2D"
view.CameraPosition = [centre, half - 0.6e-3, 0.05]
view.CameraFocalPoint = [centre, half - 0.6e-3, 0.0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelScale = half
SaveScreenshot(picture, view, ImageResolution=[900, 900])
print("wrote", picture, "at", scene.AnimationTime, "s")

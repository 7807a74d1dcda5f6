// Double-edge-notched bar (plane strain, in mm): 200 mm long (x), 100 mm high (y), with a slot
// w = 5 mm wide and a = 25 mm deep cut into each long edge at mid-length, leaving a 50 mm
// ligament. Structured triangles of h mm (transfinite blocks: the element columns line up with
// the ligament, so the smeared crack band is one column wide). Refine with h = 2.5 (w and a stay
// multiples of h).
L = 200; H = 100; a = 25; w = 5; h = 5;
xs[] = {0, 0.5 * (L - w), 0.5 * (L + w), L};
ys[] = {0, a, H - a, H};
For j In {0:3}
  For i In {0:3}
    Point(1 + i + 4 * j) = {xs[i], ys[j], 0, h};
  EndFor
EndFor
// Horizontal lines 100 + (i + 3 j), vertical lines 200 + (i + 4 j).
For j In {0:3}
  For i In {0:2}
    Line(100 + i + 3 * j) = {1 + i + 4 * j, 2 + i + 4 * j};
    Transfinite Curve{100 + i + 3 * j} = Round((xs[i + 1] - xs[i]) / h) + 1;
  EndFor
EndFor
For j In {0:2}
  For i In {0:3}
    Line(200 + i + 4 * j) = {1 + i + 4 * j, 5 + i + 4 * j};
    Transfinite Curve{200 + i + 4 * j} = Round((ys[j + 1] - ys[j]) / h) + 1;
  EndFor
EndFor
// Blocks (i, j), without the two slots (1, 0) and (1, 2).
s = 0;
For j In {0:2}
  For i In {0:2}
    If (!(i == 1 && j != 1))
      s += 1;
      Curve Loop(s) = {100 + i + 3 * j, 201 + i + 4 * j, -(103 + i + 3 * j), -(200 + i + 4 * j)};
      Plane Surface(s) = {s};
      Transfinite Surface{s};
      blocks[] += {s};
    EndIf
  EndFor
EndFor
Physical Surface("bar") = {blocks[]};
Physical Curve("left") = {200, 204, 208};
Physical Curve("right") = {203, 207, 211};

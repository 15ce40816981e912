%
(Gantry demo: a pocket outline, a circle, a helix and a row of drilled holes, in inches)
G20 G90 G17 G94 G91.1
G54
G0 Z0.5
G0 X2 Y2
G1 Z-0.1 F30
G1 X6 F120
G1 Y5
G1 X2
G1 Y2
G0 Z0.5
(a circle of radius 1 about 10, 4, cut in two full turns going down)
G0 X9 Y4
G1 Z0 F30
G2 X9 Y4 I1 J0 Z-0.1 F90
G2 X9 Y4 I1 J0
G0 Z0.5
(drill three holes, returning to the start height between them)
G98 G81 X14 Y2 Z-0.25 R0.1 F20
X15
X16
G80
G0 Z1
M2
%

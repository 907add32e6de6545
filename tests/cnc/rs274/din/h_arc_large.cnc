(h_arc_large: large arcs: 270 and 359 degree arcs by centre, a 500 mm radius, a 150 mm R arc)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-1 Z0
N60 G1 X0 Y0 Z0 F5
N70 G2 X10 Y10 Z0 I0 J10 K0 F20
N80 G3 X10 Y10 Z0 I-10 J0 K0
N90 G1 X0 Y10 Z0
N100 G3 X300 Y10 Z0 R500
N110 G2 X0 Y10 Z0 R-160
N120 G1 X65 Y100 Z0
N130 G3 X63 Y84 Z0 I-65 J0 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

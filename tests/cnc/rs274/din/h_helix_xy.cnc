(h_helix_xy: G17 helices: arcs by centre and by R with a move along the normal axis, one full turn)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y0 Z5
N60 G2 X0 Y-10 Z3 I-10 J0 K0 F10
N70 G3 X0 Y10 Z1 I0 J10 K0
N80 G2 X0 Y10 Z-4 I0 J-10 K0
N90 G3 X20 Y10 Z-6 R12
N100 G2 X0 Y10 Z-8 R-12
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_helix_xz: G18 helices: arcs by centre and by R with a move along the normal axis, one full turn)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X0 Y5 Z10
N70 G2 X-10 Y3 Z0 I0 J0 K-10 F10
N80 G3 X10 Y1 Z0 I10 J0 K0
N90 G2 X10 Y-4 Z0 I-10 J0 K0
N100 G3 X10 Y-6 Z20 R12
N110 G2 X10 Y-8 Z0 R-12
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

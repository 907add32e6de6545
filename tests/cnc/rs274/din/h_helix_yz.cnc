(h_helix_yz: G19 helices: arcs by centre and by R with a move along the normal axis, one full turn)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X5 Y10 Z0
N70 G2 X3 Y0 Z-10 I0 J-10 K0 F10
N80 G3 X1 Y0 Z10 I0 J0 K10
N90 G2 X-4 Y0 Z10 I0 J0 K-10
N100 G3 X-6 Y20 Z10 R12
N110 G2 X-8 Y0 Z10 R-12
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

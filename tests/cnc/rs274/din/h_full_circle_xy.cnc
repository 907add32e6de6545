(h_full_circle_xy: G17 full circles by centre: end point = start point)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y0 Z0
N60 G2 X10 Y0 Z0 I-10 J0 K0 F10
N70 G3 X10 Y0 Z0 I0 J5 K0
N80 G1 X30 Y0 Z0
N90 G2 X30 Y0 Z0 I3 J-4 K0
N100 G3 X30 Y0 Z0 I-0.05 J0 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_full_circle_yz: G19 full circles by centre: end point = start point)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X0 Y10 Z0
N70 G2 X0 Y10 Z0 I0 J-10 K0 F10
N80 G3 X0 Y10 Z0 I0 J0 K5
N90 G1 X0 Y30 Z0
N100 G2 X0 Y30 Z0 I0 J3 K-4
N110 G3 X0 Y30 Z0 I0 J-0.05 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

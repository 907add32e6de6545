(h_full_circle_xz: G18 full circles by centre: end point = start point)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X0 Y0 Z10
N70 G2 X0 Y0 Z10 I0 J0 K-10 F10
N80 G3 X0 Y0 Z10 I5 J0 K0
N90 G1 X0 Y0 Z30
N100 G2 X0 Y0 Z30 I-4 J0 K3
N110 G3 X0 Y0 Z30 I0 J0 K-0.05
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

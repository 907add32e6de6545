(r_arcs_yz_02: random G19 arcs by centre with exact end points, some full circles, lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X-1.753 Y7.21 Z-37.291
N70 G3 X-1.753 Y4.71 Z-49.791 I0 J0 K-6.5 F5
N80 G91
N90 G2 X0 Y25 Z10 I0 J14.5 K0 F20
N100 G3 X0 Y-0.4 Z-0.8 I0 J-15.4 K7.2
N110 G2 X0 Y-0.54 Z-0.42 I0 J0.5 K-1.2 F20
N120 G2 X0 Y0.6 Z0.8 I0 J0.3 K0.4
N130 G3 X0 Y-4 Z-8 I0 J0 K-5
N140 G2 X0 Y-6 Z-3.2 I0 J-3 K-1.6 F5
N150 G3 X0 Y-7.5 Z4.5 I0 J-7.5 K-4
N160 G3 X0 Y-20.5 Z61.5 I0 J-8 K31.5
N170 G3 X0 Y-0.9 Z2.1 I0 J-2.9 K0 F5
N180 G3 X0 Y2.5 Z0.5 I0 J1.3 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

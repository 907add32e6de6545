(r_arcs_xz_00: random G18 arcs by centre with exact end points, some full circles, lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X49.445 Y-8.998 Z-32.123
N70 G2 X49.145 Y-8.998 Z-26.723 I1.65 J0 K2.8 F10
N80 G2 X49.145 Y-8.998 Z-26.723 I-3 J0 K4 F20
N90 G3 X49.145 Y-8.998 Z-26.723 I0.15 J0 K0.2
N100 G1 X20.865 Y1.369 Z-39.562
N110 G2 X20.865 Y1.369 Z-40.862 I-4.2 J0 K-0.65
N120 G1 X36.399 Y1.369 Z-40.862
N130 G2 X36.059 Y1.369 Z-41.002 I-0.24 J0 K0.1 F5
N140 G2 X36.209 Y1.369 Z-40.552 I0 J0 K0.25
N150 G2 X34.409 Y1.369 Z-32.452 I0 J0 K4.25 F100
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

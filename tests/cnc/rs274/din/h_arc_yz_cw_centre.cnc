(h_arc_yz_cw_centre: G19 G2 arcs by J K; clockwise seen from +X: from Y10 Z0 a quarter ends at Y0 Z-10)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X0 Y10 Z0
N70 G2 X0 Y0 Z-10 I0 J-10 K0 F10
N80 G2 X0 Y-10 Z0 I0 J0 K10
N90 G2 X0 Y10 Z0 I0 J10 K0
N100 G1 X3 Y10 Z0
N110 G2 X3 Y5 Z5 I0 J-5 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

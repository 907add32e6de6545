(h_arc_yz_ccw_centre: G19 G3 arcs by J K; counterclockwise seen from +X: from Y10 Z0 a quarter ends at Y0 Z10)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X0 Y10 Z0
N70 G3 X0 Y0 Z10 I0 J-10 K0 F10
N80 G3 X0 Y-10 Z0 I0 J0 K-10
N90 G3 X0 Y10 Z0 I0 J10 K0
N100 G1 X-3 Y10 Z0
N110 G3 X-3 Y5 Z-5 I0 J-5 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

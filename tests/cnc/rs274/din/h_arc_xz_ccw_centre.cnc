(h_arc_xz_ccw_centre: G18 G3 arcs by I K; G3 is counterclockwise seen from +Y: from X10 Z0 a quarter ends at X0 Z-10)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X10 Y0 Z0
N70 G3 X0 Y0 Z-10 I-10 J0 K0 F10
N80 G3 X-10 Y0 Z0 I0 J0 K10
N90 G3 X10 Y0 Z0 I10 J0 K0
N100 G1 X10 Y0 Z5
N110 G3 X5 Y0 Z10 I-5 J0 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

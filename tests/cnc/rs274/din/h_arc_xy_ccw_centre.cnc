(h_arc_xy_ccw_centre: G17 G3 arcs by centre: quarter, half, three quarters)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y0 Z0
N60 G3 X0 Y10 Z0 I-10 J0 K0 F10
N70 G3 X0 Y-10 Z0 I0 J-10 K0
N80 G3 X-10 Y-20 Z0 I0 J-10 K0
N90 G1 X-10 Y-30 Z0
N100 G3 X-20 Y-40 Z0 I0 J-10 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

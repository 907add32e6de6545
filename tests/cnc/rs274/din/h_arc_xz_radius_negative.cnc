(h_arc_xz_radius_negative: G18 arcs by negative R: rs274 takes the arc longer than 180 degrees)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X-5 Y0 Z0
N70 G1 X0 Y0 Z0 F5
N80 G2 X0 Y0 Z20 R-15 F10
N90 G3 X0 Y0 Z40 R-15
N100 G3 X30 Y0 Z40 R-25
N110 G2 X30 Y0 Z10 R-100
N120 G2 X10 Y0 Z10 R-10.001
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

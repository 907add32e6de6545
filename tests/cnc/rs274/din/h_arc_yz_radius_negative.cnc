(h_arc_yz_radius_negative: G19 arcs by negative R: rs274 takes the arc longer than 180 degrees)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X0 Y0 Z-5
N70 G1 X0 Y0 Z0 F5
N80 G2 X0 Y20 Z0 R-15 F10
N90 G3 X0 Y40 Z0 R-15
N100 G3 X0 Y40 Z30 R-25
N110 G2 X0 Y10 Z30 R-100
N120 G2 X0 Y10 Z10 R-10.001
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

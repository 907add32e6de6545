(h_comp_right_outside_rounded: G42 around a rounded rectangle travelled counterclockwise: the tool outside, convex arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X30 Y-15 Z0
N60 G42 D2.5
N70 G1 X30 Y0 Z0 F10
N80 G1 X50 Y0 Z0
N90 G3 X60 Y10 Z0 R10
N100 G1 X60 Y30 Z0
N110 G3 X50 Y40 Z0 R10
N120 G1 X10 Y40 Z0
N130 G3 X0 Y30 Z0 R10
N140 G1 X0 Y10 Z0
N150 G3 X10 Y0 Z0 R10
N160 G1 X30 Y0 Z0
N170 G40
N180 G1 X30 Y-15 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

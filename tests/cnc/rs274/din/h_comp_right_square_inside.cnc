(h_comp_right_square_inside: G42 around a square travelled clockwise: the tool inside, inside corners)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X20 Y20 Z0
N60 G42 D3
N70 G1 X0 Y20 Z0 F10
N80 G1 X0 Y40 Z0
N90 G1 X40 Y40 Z0
N100 G1 X40 Y0 Z0
N110 G1 X0 Y0 Z0
N120 G1 X0 Y20 Z0
N130 G40
N140 G1 X20 Y20 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

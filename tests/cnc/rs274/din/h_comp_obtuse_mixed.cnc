(h_comp_obtuse_mixed: G42 along an open zigzag contour with obtuse and reflex corners, lines and arcs, with Z moves)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-10 Z5
N60 G1 X0 Y-10 Z-1 F2
N70 G42 D1
N80 G1 X0 Y0 Z-1 F10
N90 G1 X20 Y5 Z-1
N100 G1 X40 Y0 Z-1
N110 G2 X60 Y0 Z-1 R12
N120 G1 X70 Y10 Z-1
N130 G3 X90 Y10 Z-1 I10 J0 K0
N140 G1 X100 Y0 Z-1
N150 G40
N160 G1 X110 Y-10 Z-1
N170 G0 X110 Y-10 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

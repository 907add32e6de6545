(h_comp_acute_corners: G41 around a triangle with acute corners travelled clockwise, tool outside: rs274 rounds them with arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-10 Y0 Z0
N60 G41 D1.5
N70 G1 X0 Y0 Z0 F10
N80 G1 X15 Y60 Z0
N90 G1 X30 Y0 Z0
N100 G1 X0 Y0 Z0
N110 G40
N120 G1 X-10 Y0 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

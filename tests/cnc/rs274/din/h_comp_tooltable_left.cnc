(h_comp_tooltable_left: G41 D1 with the radius from the tool table, tool 1 of radius 1 mm; our D is the radius itself)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-10 Y-10 Z0
N60 G41 D1
N70 G1 X0 Y0 Z0 F10
N80 G1 X0 Y30 Z0
N90 G2 X30 Y30 Z0 R16
N100 G1 X30 Y0 Z0
N110 G1 X0 Y0 Z0
N120 G40
N130 G1 X-10 Y-10 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

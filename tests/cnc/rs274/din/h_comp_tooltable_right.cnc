(h_comp_tooltable_right: G42 D3 with the radius from the tool table, tool 3 of radius 4 mm, and G42 D2 of 2.5 mm later)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-10 Y20 Z0
N60 G42 D4
N70 G1 X0 Y20 Z0 F10
N80 G1 X0 Y60 Z0
N90 G1 X60 Y60 Z0
N100 G1 X60 Y20 Z0
N110 G1 X0 Y20 Z0
N120 G40
N130 G1 X-10 Y20 Z0
N140 G42 D2.5
N150 G1 X0 Y0 Z0
N160 G3 X40 Y0 Z0 I20 J0 K0
N170 G40
N180 G1 X50 Y0 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

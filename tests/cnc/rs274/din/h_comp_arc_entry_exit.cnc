(h_comp_arc_entry_exit: G42 with an arc as the entry move and an arc before the exit line)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-20 Y-20 Z0
N60 G42 D2
N70 G2 X0 Y0 Z0 R20 F10
N80 G1 X30 Y0 Z0
N90 G2 X40 Y-10 Z0 I0 J-10 K0
N100 G1 X40 Y-30 Z0
N110 G40
N120 G1 X20 Y-40 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(r_comp_01: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X59.041 Y-62.862 Z5
N60 G1 X59.041 Y-62.862 Z-1 F10
N70 G42 D2
N80 G1 X45.2 Y-51.35 Z-1
N90 G1 X7.36 Y-66.29 Z-1 F25
N100 G1 X-33.04 Y-53.9 Z-1 F12.5
N110 G1 X-42.19 Y-27.78 Z-1
N120 G2 X-38.65 Y0.84 Z-1 R41.938
N130 G1 X5.9 Y13.29 Z-1 F12.5
N140 G2 X40.91 Y25.44 Z-1 R38.198
N150 G1 X26.34 Y-10.64 Z-1 F100
N160 G2 X45.2 Y-51.35 Z-1 R58.088
N170 G1 X26.28 Y-58.82 Z-1
N180 G40
N190 G1 X59.041 Y-62.862 Z-1
N200 G0 X59.041 Y-62.862 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

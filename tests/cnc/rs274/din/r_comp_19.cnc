(r_comp_19: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X15.52 Y-42.804 Z5
N60 G1 X15.52 Y-42.804 Z0 F25
N70 G42 D3
N80 G1 X2.87 Y-29.91 Z0
N90 G3 X-24.94 Y-40.31 Z0 R26.967
N100 G1 X-56.88 Y-33.66 Z0
N110 G1 X-58.78 Y48.31 Z0
N120 G2 X-32.71 Y50.71 Z0 R34.197
N130 G1 X-15.29 Y25.6 Z0
N140 G1 X2.87 Y-29.91 Z0 F100
N150 G40
N160 G1 X15.52 Y-42.804 Z0
N170 G0 X15.52 Y-42.804 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

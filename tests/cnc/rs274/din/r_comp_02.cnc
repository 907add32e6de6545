(r_comp_02: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X4.687 Y8.441 Z5
N60 G1 X4.687 Y8.441 Z0 F100
N70 G41 D2.5
N80 G1 X-5.61 Y-0.73 Z0
N90 G2 X-37.62 Y7.57 Z0 R35.251
N100 G1 X-65.63 Y-16.85 Z0
N110 G1 X-64.94 Y-49.69 Z0
N120 G2 X-48.21 Y-63.9 Z0 R12.492
N130 G1 X27.69 Y-38.88 Z0
N140 G1 X-5.61 Y-0.73 Z0 F12.5
N150 G40
N160 G1 X4.687 Y8.441 Z0
N170 G0 X4.687 Y8.441 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

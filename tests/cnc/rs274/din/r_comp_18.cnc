(r_comp_18: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-19.126 Y59.395 Z5
N60 G1 X-19.126 Y59.395 Z-1 F2.5
N70 G91
N80 G42 D1.5
N90 G1 X-1.504 Y-14.585 Z0 F12.5
N100 G1 X-22.26 Y3.32 Z0
N110 G1 X-31.69 Y-12.09 Z0
N120 G1 X35.28 Y-48.53 Z0
N130 G1 X40 Y-26.93 Z0
N140 G1 X-21.33 Y84.23 Z0
N150 G40
N160 G1 X1.504 Y14.585 Z0
N170 G90
N180 G0 X-19.126 Y59.395 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

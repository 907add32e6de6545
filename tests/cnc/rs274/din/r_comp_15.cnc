(r_comp_15: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-26.572 Y58.168 Z5
N60 G1 X-26.572 Y58.168 Z-1 F20
N70 G91
N80 G42 D1
N90 G1 X3.072 Y-13.438 Z0
N100 G2 X-37.12 Y-35.3 Z0 R44.752
N110 G1 X26.6 Y-59.19 Z0
N120 G1 X47.2 Y1.42 Z0
N130 G1 X8.24 Y28.4 Z0
N140 G1 X-44.92 Y64.67 Z0
N150 G40
N160 G1 X-3.072 Y13.438 Z0
N170 G90
N180 G0 X-26.572 Y58.168 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(r_comp_14: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X20.781 Y-52.184 Z5
N60 G1 X20.781 Y-52.184 Z-1 F50
N70 G91
N80 G42 D1.5
N90 G1 X-0.921 Y15.524 Z0
N100 G1 X-28.21 Y-14.33 Z0 F12.5
N110 G1 X-28.49 Y34.54 Z0
N120 G1 X10.71 Y35.31 Z0
N130 G1 X59.1 Y3.55 Z0
N140 G3 X24.88 Y-11.68 Z0 R34.678
N150 G2 X-37.99 Y-47.39 Z0 R38.753
N160 G1 X-14.105 Y-7.165 Z0
N170 G40
N180 G1 X15.026 Y-8.359 Z0
N190 G90
N200 G0 X20.781 Y-52.184 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

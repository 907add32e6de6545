(r_comp_11: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X1.46 Y-40.282 Z5
N60 G1 X1.46 Y-40.282 Z0 F2.5
N70 G42 D1
N80 G1 X9.13 Y-22.77 Z0
N90 G3 X4.79 Y40.55 Z0 R47.297
N100 G1 X57.97 Y35.66 Z0 F2.5
N110 G2 X9.13 Y-22.77 Z0 R63.044 F5
N120 G40
N130 G1 X1.46 Y-40.282 Z0
N140 G0 X1.46 Y-40.282 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

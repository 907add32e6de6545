(r_comp_07: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X7.344 Y-43.471 Z5
N60 G1 X7.344 Y-43.471 Z-1 F5
N70 G91
N80 G41 D0.5
N90 G1 X-13.744 Y5.451 Z0
N100 G1 X-41.13 Y-26.82 Z0
N110 G2 X-38.85 Y54.82 Z0 R66.614
N120 G2 X56.01 Y3.22 Z0 R44.37
N130 G1 X44.7 Y-12.65 Z0 F2.5
N140 G1 X-20.73 Y-18.57 Z0
N150 G1 X-20.565 Y-13.41 Z0
N160 G40
N170 G1 X34.309 Y7.959 Z0
N180 G90
N190 G0 X7.344 Y-43.471 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

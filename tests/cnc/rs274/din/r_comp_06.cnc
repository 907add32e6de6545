(r_comp_06: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X9.233 Y-28.571 Z5
N60 G1 X9.233 Y-28.571 Z0 F5
N70 G42 D1
N80 G1 X11.81 Y-16.29 Z0 F100
N90 G1 X-8.48 Y33.29 Z0
N100 G1 X64.82 Y25.47 Z0
N110 G1 X11.81 Y-16.29 Z0
N120 G1 X1.665 Y8.5 Z0
N130 G40
N140 G1 X9.233 Y-28.571 Z0
N150 G0 X9.233 Y-28.571 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(r_comp_17: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X22.561 Y-26.947 Z5
N60 G1 X22.561 Y-26.947 Z0 F12.5
N70 G42 D4
N80 G1 X15.71 Y-21.04 Z0
N90 G1 X-6.57 Y-55.73 Z0
N100 G1 X-32.74 Y-11.24 Z0
N110 G2 X-50.55 Y4.67 Z0 R22.489 F25
N120 G1 X-59.41 Y28.78 Z0
N130 G1 X-23.54 Y42.38 Z0
N140 G1 X3.28 Y47.42 Z0 F25
N150 G3 X17.87 Y15.22 Z0 R52.376
N160 G1 X15.71 Y-21.04 Z0
N170 G1 X4.57 Y-38.385 Z0
N180 G40
N190 G1 X22.561 Y-26.947 Z0
N200 G0 X22.561 Y-26.947 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

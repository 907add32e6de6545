(r_comp_10: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X48.611 Y27.804 Z5
N60 G1 X48.611 Y27.804 Z-1 F10
N70 G42 D0.5
N80 G1 X32.64 Y16.49 Z-1
N90 G1 X-3.29 Y40.48 Z-1
N100 G2 X-32.85 Y17.29 Z-1 R27.938 F100
N110 G2 X-38.9 Y-4.45 Z-1 R15.834
N120 G1 X-45.43 Y-33.36 Z-1 F12.5
N130 G1 X-14.96 Y-61.06 Z-1
N140 G1 X0.62 Y-44.72 Z-1
N150 G3 X22.86 Y-37.85 Z-1 R25.275
N160 G1 X32.64 Y16.49 Z-1
N170 G1 X14.675 Y28.485 Z-1
N180 G40
N190 G1 X48.611 Y27.804 Z-1
N200 G0 X48.611 Y27.804 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

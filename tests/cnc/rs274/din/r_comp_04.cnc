(r_comp_04: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X1.883 Y3.28 Z5
N60 G1 X1.883 Y3.28 Z-1 F20
N70 G41 D2
N80 G1 X-6.29 Y12.04 Z-1
N90 G1 X-17.15 Y1.08 Z-1
N100 G1 X-32.78 Y9.32 Z-1
N110 G3 X-42.97 Y50.74 Z-1 R32.624
N120 G2 X-33.98 Y76.83 Z-1 R35.213
N130 G3 X-9.3 Y61.91 Z-1 R23.607
N140 G3 X-6.29 Y12.04 Z-1 R68.591
N150 G1 X-11.72 Y6.56 Z-1
N160 G40
N170 G1 X1.883 Y3.28 Z-1
N180 G0 X1.883 Y3.28 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

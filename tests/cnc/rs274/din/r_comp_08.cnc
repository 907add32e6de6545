(r_comp_08: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X87.747 Y10.883 Z5
N60 G1 X87.747 Y10.883 Z-1 F25
N70 G41 D4
N80 G1 X72.1 Y13.06 Z-1
N90 G1 X-0.18 Y-22.69 Z-1
N100 G1 X2.24 Y13.7 Z-1
N110 G1 X41.23 Y45.85 Z-1
N120 G3 X72.1 Y13.06 Z-1 R47.061
N130 G1 X35.96 Y-4.815 Z-1
N140 G40
N150 G1 X87.747 Y10.883 Z-1
N160 G0 X87.747 Y10.883 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

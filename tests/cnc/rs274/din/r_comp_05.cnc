(r_comp_05: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X65.327 Y60.692 Z5
N60 G1 X65.327 Y60.692 Z-2.5 F50
N70 G41 D2
N80 G1 X52.34 Y51.65 Z-2.5
N90 G3 X-10.78 Y52.55 Z-2.5 R40.428
N100 G1 X-1.62 Y7.98 Z-2.5
N110 G2 X3.65 Y-26.36 Z-2.5 R47.529 F10
N120 G1 X32.19 Y-13.7 Z-2.5
N130 G3 X63.54 Y8.06 Z-2.5 R52.521
N140 G1 X52.34 Y51.65 Z-2.5
N150 G40
N160 G1 X65.327 Y60.692 Z-2.5
N170 G0 X65.327 Y60.692 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

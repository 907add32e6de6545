(r_comp_12: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X51.043 Y70.11 Z5
N60 G1 X51.043 Y70.11 Z-1 F2.5
N70 G41 D2
N80 G1 X48.76 Y61.44 Z-1
N90 G2 X-6.93 Y-2.95 Z-1 R82.727
N100 G1 X56.27 Y-6.02 Z-1
N110 G1 X48.76 Y61.44 Z-1
N120 G40
N130 G1 X51.043 Y70.11 Z-1
N140 G0 X51.043 Y70.11 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

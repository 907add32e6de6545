(r_comp_00: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X27.255 Y7.113 Z5
N60 G1 X27.255 Y7.113 Z-2.5 F50
N70 G41 D1
N80 G1 X9.72 Y11.99 Z-2.5
N90 G1 X-10.36 Y-21.76 Z-2.5
N100 G3 X-37.29 Y0.65 Z-2.5 R23.657 F20
N110 G1 X-75.81 Y16.5 Z-2.5
N120 G1 X-38.85 Y46.26 Z-2.5
N130 G2 X-8.97 Y63.67 Z-2.5 R50.694
N140 G1 X8.17 Y42.3 Z-2.5
N150 G1 X9.72 Y11.99 Z-2.5 F2.5
N160 G1 X-0.32 Y-4.885 Z-2.5
N170 G40
N180 G1 X27.255 Y7.113 Z-2.5
N190 G0 X27.255 Y7.113 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

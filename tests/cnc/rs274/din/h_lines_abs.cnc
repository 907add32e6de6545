(h_lines_abs: G0 and G1 lines in absolute coordinates)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y5 Z2
N60 G1 X30 Y5 Z2 F10
N70 G1 X30 Y25.5 Z2
N80 G1 X-12.25 Y25.5 Z-3
N90 G1 X0 Y0 Z0
N100 G0 X0 Y0 Z10
N110 G0 X100 Y-50 Z10
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

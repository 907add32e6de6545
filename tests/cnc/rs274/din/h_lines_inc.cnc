(h_lines_inc: G0 and G1 lines in incremental coordinates G91)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G91
N60 G0 X5 Y5 Z1
N70 G1 X10 Y0 Z0 F20
N80 G1 X0 Y10 Z0
N90 G1 X-10 Y0 Z-2.5
N100 G1 X0 Y-10 Z0
N110 G0 X0 Y0 Z11.5
N120 G1 X-4.999 Y-4.998 Z-0.001
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

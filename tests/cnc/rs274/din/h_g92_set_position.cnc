(h_g92_set_position: G92 sets the current position without motion, in absolute mode only)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y10 Z10
N60 G1 X20 Y10 Z10 F10
N70 G92 X0 Y0 Z0
N80 G1 X5 Y5 Z0
N90 G2 X15 Y5 Z0 I5 J0 K0
N100 G92 X100 Y-20 Z3.5
N110 G1 X110 Y-20 Z3.5
N120 G0 X0 Y-1 Z0
N130 G1 X0 Y0 Z0 F5
N140 G92 X1 Y2 Z3
N150 G1 X1 Y2 Z4
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

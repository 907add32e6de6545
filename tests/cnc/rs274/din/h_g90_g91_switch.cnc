(h_g90_g91_switch: G90 and G91 switched between lines and arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y10 Z0
N60 G91
N70 G1 X10 Y0 Z0 F5
N80 G2 X10 Y10 Z0 I0 J10 K0
N90 G90
N100 G1 X30 Y40 Z0
N110 G91
N120 G3 X-10 Y10 Z0 I-10 J0 K0
N130 G1 X0 Y0 Z-2
N140 G90
N150 G1 X0 Y0 Z-2
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_mixed_planes: arcs and helices while switching G17, G18, G19 and G90/G91)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-1 Z0
N60 G1 X0 Y0 Z0 F5
N70 G2 X10 Y10 Z0 I10 J0 K0 F10
N80 G18
N90 G3 X20 Y10 Z10 I10 J0 K0
N100 G19
N110 G91
N120 G2 X0 Y10 Z-10 I0 J10 K0
N130 G17
N140 G3 X10 Y10 Z-5 R10
N150 G90
N160 G18
N170 G2 X30 Y35 Z-15 R-8
N180 G17
N190 G1 X0 Y0 Z0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_comp_incremental: G41 with the contour written in G91 incremental coordinates)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-5 Y-5 Z0
N60 G91
N70 G41 D2
N80 G1 X5 Y5 Z0 F10
N90 G1 X30 Y0 Z0
N100 G3 X0 Y20 Z0 I0 J10 K0
N110 G1 X-30 Y0 Z0
N120 G1 X0 Y-20 Z0
N130 G40
N140 G1 X-5 Y-5 Z0
N150 G90
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

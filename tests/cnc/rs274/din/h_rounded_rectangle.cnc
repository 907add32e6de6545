(h_rounded_rectangle: a closed contour of lines and tangent quarter arcs, counterclockwise)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X10 Y0 Z0
N60 G1 X10 Y0 Z-1 F5
N70 G1 X50 Y0 Z-1 F20
N80 G3 X60 Y10 Z-1 I0 J10 K0
N90 G1 X60 Y30 Z-1
N100 G3 X50 Y40 Z-1 I-10 J0 K0
N110 G1 X10 Y40 Z-1
N120 G3 X0 Y30 Z-1 R10
N130 G1 X0 Y10 Z-1
N140 G3 X10 Y0 Z-1 R10
N150 G0 X10 Y0 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

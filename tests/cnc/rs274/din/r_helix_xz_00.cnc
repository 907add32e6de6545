(r_helix_xz_00: random G18 helices by centre, some full turns)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X29.835 Y10.673 Z-1.418
N70 G2 X29.585 Y-1.158 Z8.832 I5 J0 K5.25 F20
N80 G3 X28.985 Y8.012 Z8.432 I3.3 J0 K-5.6
N90 G1 X48.129 Y-9.059 Z-20.797
N100 G91
N110 G1 X-15.439 Y-32.166 Z0 F5
N120 G2 X6.2 Y1.868 Z-3.4 I4.8 J0 K1.4
N130 G3 X-4 Y2.912 Z3 I1.6 J0 K6.3
N140 G3 X-1.6 Y12.992 Z-0.8 I-0.6 J0 K-0.8
N150 G3 X-2.4 Y2.831 Z-3.2 I-1.2 J0 K-1.6
N160 G3 X0 Y12.189 Z8.4 I4 J0 K4.2
N170 G3 X8.8 Y0 Z-1.6 I4 J0 K-3
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

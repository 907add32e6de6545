(r_helix_xy_01: random G17 helices by centre, some full turns)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X20.135 Y-47.386 Z-43.937
N60 G1 X-11.987 Y-47.386 Z-55.309 F25
N70 G3 X-11.687 Y-47.486 Z-72.095 I0.3 J0.4 K0
N80 G2 X-8.187 Y-38.986 Z-72.095 I6 J2.5 K0
N90 G3 X-10.387 Y-40.086 Z-72.095 I-1.2 J-0.35 K0
N100 G2 X-12.587 Y-44.486 Z-79.777 I-4.2 J-0.65 K0
N110 G2 X-11.787 Y-44.086 Z-82.413 I1.5 J-2 K0
N120 G2 X-26.787 Y-44.086 Z-81.095 I-7.5 J4 K0
N130 G2 X-17.787 Y-17.086 Z-81.095 I24 J7 K0
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

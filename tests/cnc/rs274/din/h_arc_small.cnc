(h_arc_small: tiny arcs: radius 0.1 mm, sweeps of a few degrees, a 0.05 mm full circle)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-1 Z0
N60 G1 X0 Y0 Z0 F5
N70 G3 X0.2 Y0 Z0 I0.1 J0 K0 F1
N80 G2 X0.34 Y0.02 Z0 I0.08 J-0.06 K0
N90 G1 X50 Y0.02 Z0
N100 G3 X47 Y9.02 Z0 I-63 J-16 K0
N110 G2 X50 Y0.02 Z0 I-60 J-25 K0
N120 G2 X50 Y0.02 Z0 I0.03 J0.04 K0
N130 G3 X50.05 Y0.02 Z0 R0.03
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

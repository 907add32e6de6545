(h_dwell: dwells between moves: G4 P<s> in rs274, G4 T<s> in our dialect)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y0 Z5
N60 G4 T0.5
N70 G1 X0 Y0 Z0 F2
N80 G4 T2
N90 G1 X10 Y0 Z0
N100 G4 T0.001
N110 G3 X20 Y0 Z0 I5 J0 K0
N120 G4 T1.25
N130 G0 X20 Y0 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_feed_changes: feed changes on lines and arcs: rs274 F in mm/min is 60 x our F in mm/s)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-1 Z0
N60 G1 X0 Y0 Z0 F5
N70 G1 X10 Y0 Z0 F1
N80 G1 X20 Y0 Z0 F12.5
N90 G2 X30 Y0 Z0 I5 J0 K0 F100
N100 G1 X30 Y10 Z0 F0.5
N110 G1 X30 Y20 Z0
N120 G3 X20 Y20 Z0 R6 F25
N130 G1 X0 Y20 Z-1 F250
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(h_arc_xy_radius: G17 arcs by positive R: the arc of at most 180 degrees, G2 and G3)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X0 Y-5 Z0
N60 G1 X0 Y0 Z0 F5
N70 G2 X20 Y0 Z0 R15 F10
N80 G3 X40 Y0 Z0 R15
N90 G3 X40 Y30 Z0 R25
N100 G2 X10 Y30 Z0 R100
N110 G3 X10 Y10 Z0 R10.001
N120 G2 X0 Y0 Z0 R50 F5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

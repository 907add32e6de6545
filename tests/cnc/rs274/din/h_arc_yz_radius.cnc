(h_arc_yz_radius: G19 arcs by positive R: the arc of at most 180 degrees, G2 and G3)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X0 Y0 Z-5
N70 G1 X0 Y0 Z0 F5
N80 G2 X0 Y20 Z0 R15 F10
N90 G3 X0 Y40 Z0 R15
N100 G3 X0 Y40 Z30 R25
N110 G2 X0 Y10 Z30 R100
N120 G3 X0 Y10 Z10 R10.001
N130 G2 X0 Y0 Z0 R50 F5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

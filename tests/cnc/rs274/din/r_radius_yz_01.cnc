(r_radius_yz_01: random G19 arcs by positive R, some helical, and lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X16.117 Y-37.401 Z15.651
N70 G1 X31.224 Y-12.316 Z46.274 F20
N80 G91
N90 G3 X0 Y-35.104 Z-32.185 R73.173
N100 G2 X0 Y-38.589 Z-22.824 R56.312
N110 G1 X0 Y33.31 Z-3.177
N120 G1 X-23.361 Y0 Z0
N130 G2 X0 Y-25.604 Z7.733 R14.916
N140 G2 X0 Y-33.465 Z-34.166 R35.001
N150 G3 X-1.363 Y35.548 Z18.575 R49.695 F12.5
N160 G1 X34.25 Y0 Z-4.996 F25
N170 G2 X-9.777 Y20.943 Z-39.098 R26.821
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

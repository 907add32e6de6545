(r_radius_xy_02: random G17 arcs by positive R, some helical, and lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-45.5 Y40.717 Z-17.819
N60 G2 X-60.94 Y12.816 Z-15.207 R61.926 F100
N70 G3 X-23.344 Y13.652 Z-22.359 R31.657 F10
N80 G91
N90 G1 X0 Y0 Z-9.876
N100 G90
N110 G1 X7.401 Y-7.742 Z-2.018
N120 G3 X19.547 Y31.862 Z-2.018 R28.124
N130 G2 X-8.627 Y8.671 Z-2.018 R36.795
N140 G2 X-17.402 Y-0.363 Z-2.018 R8.801
N150 G2 X-20.514 Y0.074 Z-2.018 R2.917
N160 G1 X-7.778 Y9.293 Z-39.097
N170 G1 X5.997 Y9.293 Z-32.231
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

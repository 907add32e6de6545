(r_radius_yz_00: random G19 arcs by positive R, some helical, and lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X-9.534 Y17.983 Z43.35
N70 G2 X-8.299 Y42.668 Z16.961 R69.987 F2.5
N80 G2 X-8.299 Y47.983 Z-17.374 R67.31
N90 G1 X-20.498 Y47.983 Z-15.54
N100 G2 X-21.607 Y40.245 Z-23.244 R6.758
N110 G3 X-21.607 Y2.143 Z-48.2 R52.543 F50
N120 G1 X-53.371 Y-18.563 Z-54.449 F10
N130 G3 X-46.893 Y-5.377 Z-76.723 R14.709
N140 G2 X-46.893 Y29.13 Z-61.321 R67.9
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

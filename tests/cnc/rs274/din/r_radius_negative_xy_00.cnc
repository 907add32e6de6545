(r_radius_negative_xy_00: random G17 arcs by R, about half negative: longer than 180 degrees)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X43.693 Y43.178 Z-6.391
N60 G3 X61.954 Y27.057 Z-7.799 R20.354 F20
N70 G2 X57.475 Y31.313 Z-7.799 R-3.294 F50
N80 G2 X54.048 Y63.987 Z-7.799 R-42.378 F50
N90 G2 X72.52 Y42.779 Z-7.799 R-29.013 F12.5
N100 G3 X59.489 Y38.583 Z-7.799 R10.56 F100
N110 G91
N120 G3 X32.164 Y37.49 Z0 R27.954
N130 G2 X-27.942 Y26.859 Z0 R61.909 F12.5
N140 G3 X20.334 Y-39.694 Z0 R80.69
N150 G1 X-35.5 Y-11.731 Z0
N160 G2 X-30.403 Y-18.5 Z0 R65.564
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(r_radius_negative_yz_00: random G19 arcs by R, about half negative: longer than 180 degrees)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G19
N60 G0 X-5.432 Y36.913 Z-43.45
N70 G3 X-5.432 Y42.743 Z-5.439 R-69.883 F25
N80 G3 X-5.432 Y10.267 Z23.039 R28.773 F50
N90 G3 X-5.432 Y44.543 Z0.934 R41.371 F5
N100 G2 X-0.162 Y60.265 Z25.57 R34.919
N110 G1 X-0.162 Y72.377 Z39.355
N120 G1 X-24.789 Y54.816 Z55.127
N130 G91
N140 G2 X0 Y31.02 Z-1.652 R-41.734 F5
N150 G90
N160 G1 X-50.646 Y88.037 Z60.593 F5
N170 G2 X-50.646 Y105.125 Z77.826 R31.248
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

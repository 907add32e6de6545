(r_radius_xz_01: random G18 arcs by positive R, some helical, and lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X11.155 Y-22.77 Z-17.27
N70 G1 X21.549 Y-21.297 Z-17.27 F5
N80 G1 X28.138 Y-1.317 Z-33.569
N90 G2 X13.604 Y-1.317 Z-16.844 R11.999
N100 G1 X-10.617 Y-1.317 Z-16.844 F10
N110 G91
N120 G3 X11.519 Y9.189 Z36.859 R20.879
N130 G2 X36.992 Y0 Z0.715 R26.625
N140 G2 X-16.224 Y0 Z35.958 R26.153
N150 G2 X22.225 Y-3.338 Z35.721 R80.926 F25
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

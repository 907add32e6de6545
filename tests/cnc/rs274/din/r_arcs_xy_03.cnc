(r_arcs_xy_03: random G17 arcs by centre with exact end points, some full circles, lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X44.5 Y9.036 Z19.803
N60 G2 X44.5 Y6.636 Z19.803 I0.5 J-1.2 K0 F2.5
N70 G1 X39.343 Y39.953 Z56.663 F2.5
N80 G2 X41.093 Y39.703 Z56.663 I1 J0.75 K0
N90 G3 X51.093 Y49.703 Z56.663 I0 J10 K0
N100 G2 X51.453 Y49.583 Z56.663 I0.2 J0 K0
N110 G3 X75.953 Y39.083 Z56.663 I14.5 J0 K0
N120 G2 X115.953 Y9.083 Z56.663 I20 J-15 K0 F50
N130 G2 X115.953 Y9.083 Z56.663 I0 J-7.25 K0 F2.5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

(r_arcs_xz_02: random G18 arcs by centre with exact end points, some full circles, lines)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G18
N60 G0 X-16.972 Y24.427 Z30.363
N70 G1 X-43.698 Y24.427 Z30.363 F100
N80 G3 X-31.298 Y24.427 Z21.563 I15 J0 K8
N90 G91
N100 G2 X-1.6 Y0 Z-4 I4.2 J0 K-4
N110 G3 X0.02 Y0 Z0.82 I-0.4 J0 K0.42 F5
N120 G3 X-6.4 Y0 Z-1.6 I-3 J0 K-1.6 F2.5
N130 G2 X-8.7 Y0 Z-14.5 I-5.1 J0 K-6.8
N140 G3 X8.5 Y0 Z-8.5 I2.5 J0 K-6 F25
N150 G3 X0 Y0 Z0 I-4 J0 K-7.5
N160 G2 X-0.8 Y0 Z1.6 I11.2 J0 K6.6
N170 G2 X0 Y0 Z0 I-4.2 J0 K4 F2.5
N180 G2 X2 Y0 Z4 I12 J0 K-3.5
N190 G2 X-0.34 Y0 Z0.14 I-0.1 J0 K0.24
N200 G3 X-1 Y0 Z-0.5 I-1 J0 K0.75
N210 G2 X-0.3 Y0 Z0.9 I-0.3 J0 K0.4
N220 G3 X-17 Y0 Z0 I-8.5 J0 K0
N230 G90
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

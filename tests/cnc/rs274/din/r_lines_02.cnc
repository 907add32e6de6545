(r_lines_02: random G0/G1 lines, G90/G91 switches, feed changes)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X26.514 Y-20.044 Z-38.73
N60 G1 X42.044 Y-20.044 Z-12.691 F50
N70 G91
N80 G1 X-13.439 Y-18.172 Z0
N90 G1 X-25.28 Y27.038 Z-7.601
N100 G90
N110 G1 X-14.266 Y28 Z-20.292
N120 G0 X-40.358 Y-6.992 Z-46.613
N130 G91
N140 G1 X-22.801 Y0 Z0 F5
N150 G1 X-5.333 Y0 Z18.61 F25
N160 G1 X0 Y10.036 Z0
N170 G1 X36.822 Y0 Z39.422
N180 G1 X-23.983 Y-28.598 Z22.715
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

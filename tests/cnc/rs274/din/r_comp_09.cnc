(r_comp_09: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X52.794 Y-6.52 Z5
N60 G1 X52.794 Y-6.52 Z0 F2.5
N70 G91
N80 G41 D2.5
N90 G1 X-12.294 Y-8.59 Z0
N100 G1 X-7.5 Y31.13 Z0
N110 G1 X-21.95 Y-9.2 Z0
N120 G2 X-27.86 Y-5.67 Z0 R39.116 F12.5
N130 G3 X4.23 Y-38.87 Z0 R48.105
N140 G1 X63.71 Y-36.08 Z0 F50
N150 G1 X20.23 Y28.72 Z0
N160 G3 X-30.86 Y29.97 Z0 R33.963
N170 G1 X-3.75 Y15.565 Z0
N180 G40
N190 G1 X16.044 Y-6.975 Z0
N200 G90
N210 G0 X52.794 Y-6.52 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

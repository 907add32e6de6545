(r_comp_03: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X-28.003 Y-48.929 Z5
N60 G1 X-28.003 Y-48.929 Z-2.5 F20
N70 G42 D4
N80 G1 X-17.46 Y-34.64 Z-2.5
N90 G3 X-33.51 Y25.46 Z-2.5 R34.829
N100 G1 X43.1 Y3.25 Z-2.5 F12.5
N110 G2 X-17.46 Y-34.64 Z-2.5 R48.209
N120 G40
N130 G1 X-28.003 Y-48.929 Z-2.5
N140 G0 X-28.003 Y-48.929 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

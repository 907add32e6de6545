(r_comp_16: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X24.903 Y-25.989 Z5
N60 G1 X24.903 Y-25.989 Z0 F12.5
N70 G41 D1
N80 G1 X11.09 Y-20.93 Z0 F50
N90 G1 X-56.69 Y-29.56 Z0
N100 G1 X-86.93 Y-21.78 Z0
N110 G1 X-92.72 Y14.35 Z0 F50
N120 G2 X-10.1 Y46.04 Z0 R111.104
N130 G1 X-17.49 Y5.12 Z0
N140 G1 X11.09 Y-20.93 Z0 F50
N150 G1 X-22.8 Y-25.245 Z0
N160 G40
N170 G1 X24.903 Y-25.989 Z0
N180 G0 X24.903 Y-25.989 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

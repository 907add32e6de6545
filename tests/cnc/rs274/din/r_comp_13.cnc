(r_comp_13: random closed contour with tool radius compensation, lines and R arcs)
(rs274 has G21 G91.1 here: millimetres, I J K relative to the start point)
N30 G17
N40 G90
N50 G0 X104.653 Y-4.045 Z5
N60 G1 X104.653 Y-4.045 Z-1 F25
N70 G42 D3
N80 G1 X90.76 Y-9.37 Z-1
N90 G1 X8.2 Y12.3 Z-1
N100 G1 X37.18 Y-66.71 Z-1
N110 G1 X90.76 Y-9.37 Z-1
N120 G1 X49.48 Y1.465 Z-1
N130 G40
N140 G1 X104.653 Y-4.045 Z-1
N150 G0 X104.653 Y-4.045 Z5
(end of program: rs274 has M2 here, an M-function handshake in our dialect)

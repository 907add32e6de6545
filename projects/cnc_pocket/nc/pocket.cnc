%pocket
(a 50 x 40 pocket outline with R10 corners at the top, cut 2 deep with a 4 mm cutter)
N10 G0 X0 Y0 Z5 F200 E2000 E-2000
N20 M10 (spindle on: the PLC acknowledges once it is at speed)
N30 G1 Z-2 F20 E200 E-200
N40 G41 G1 X10 Y10 D2 F50 E500 E-500
N50 G1 X50
N60 G3 X60 Y20 I0 J10
N70 G1 Y40
N80 G3 X50 Y50 I-10 J0
N90 G1 X10
N100 G1 Y10
N110 G40 G1 X0 Y0
N120 G0 Z5 F200 E2000 E-2000
N130 M11 (spindle off)

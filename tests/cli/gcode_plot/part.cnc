%part
(stc plot --gcode: rapids, lines, arcs, a spline run and an ellipse; tests/cli/plot_test.py)
N10 G0 X10 Y0
N20 G1 X50 Y0 F100 E1000 E-1000
N30 G3 X50 Y30 I0 J15        ; half circle counter-clockwise around (50,15), radius 15
N40 G1 X30 Y30
N50 G5 X20 Y40
N60 G5 X10 Y30
N70 G1 X10 Y0
N80 G0 X30 Y15 Z5
N90 G1 Z-1
N100 G2 X30 Y15 I5 J0        ; full circle clockwise around (35,15), radius 5
N110 G0 Z5
N120 G9 X10 Y15 I-10 J0 R0.5  ; half an ellipse counter-clockwise around (20,15), a = 10 along X, b = 5
N130 G0 X0 Y0 Z10

(a contour whose numbers come from the GVL)
N10 G0 X0 Y0
N20 G1 X$xPos$ Y0 F100 E1000 E-1000
N30 G2 X$GVL.xPos$ Y10 R$radius$
N40 G1 X0 Y10

N10 G0 X0 Y0
N20 G1 X$len$ Y0 F100
N30 G3 X$len$ Y$h$ R$radius$

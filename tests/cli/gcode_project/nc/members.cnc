(names the run-time lookup takes: an array element, GVL-qualified, a PROGRAM variable)
N10 G1 X$tbl[2]$ Y$GVL.tbl[1]$ F100
N20 G1 X$Main.yOff$

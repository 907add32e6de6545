(no moves at all)
N10 G90

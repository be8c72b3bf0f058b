# Table 6.1 variants, landscape: frame time and hit rate over the camera path (make_tables).
set terminal pngcairo size 1400,500 noenhanced
set output 't61_landscape.png'
set multiplot layout 1,2 title "Table 6.1 variants, landscape"
set xlabel 'camera (frame of the path)'
set key outside bottom center horizontal
set ylabel 'GPU ms/frame'
set logscale y
plot 't61_landscape.dat' index 0 using 1:2 with linespoints pt 7 ps 0.3 title "No memoization", \
     't61_landscape.dat' index 1 using 1:2 with linespoints pt 7 ps 0.3 title "Non-tiled", \
     't61_landscape.dat' index 2 using 1:2 with linespoints pt 7 ps 0.3 title "Tiled, nearest neighbour", \
     't61_landscape.dat' index 3 using 1:2 with linespoints pt 7 ps 0.3 title "Tiled, bilinear", \
     't61_landscape.dat' index 4 using 1:2 with linespoints pt 7 ps 0.3 title "Non-tiled*", \
     't61_landscape.dat' index 5 using 1:2 with linespoints pt 7 ps 0.3 title "Tiled, nearest neighbour*", \
     't61_landscape.dat' index 6 using 1:2 with linespoints pt 7 ps 0.3 title "Tiled, bilinear*", \
     't61_landscape.dat' index 7 using 1:2 with linespoints pt 7 ps 0.3 title "Floor (constant materials)"
unset logscale y
set ylabel 'hit rate (%)'
plot 't61_landscape.dat' index 1 using 1:3 with lines title "Non-tiled", \
     't61_landscape.dat' index 2 using 1:3 with lines title "Tiled, nearest neighbour", \
     't61_landscape.dat' index 3 using 1:3 with lines title "Tiled, bilinear", \
     't61_landscape.dat' index 4 using 1:3 with lines title "Non-tiled*", \
     't61_landscape.dat' index 5 using 1:3 with lines title "Tiled, nearest neighbour*", \
     't61_landscape.dat' index 6 using 1:3 with lines title "Tiled, bilinear*"
unset multiplot

# Eviction, classroom, tile, 2^21 texels: frame time and hit rate over the camera path (make_tables).
set terminal pngcairo size 1400,500 noenhanced
set output 't62_tile_s21.png'
set multiplot layout 1,2 title "Eviction, classroom, tile, 2^21 texels"
set xlabel 'camera (frame of the path)'
set key outside bottom center horizontal
set ylabel 'GPU ms/frame'
set logscale y
plot 't62_tile_s21.dat' index 0 using 1:2 with linespoints pt 7 ps 0.3 title "No eviction", \
     't62_tile_s21.dat' index 1 using 1:2 with linespoints pt 7 ps 0.3 title "Random", \
     't62_tile_s21.dat' index 2 using 1:2 with linespoints pt 7 ps 0.3 title "LRW frame", \
     't62_tile_s21.dat' index 3 using 1:2 with linespoints pt 7 ps 0.3 title "LRU frame", \
     't62_tile_s21.dat' index 4 using 1:2 with linespoints pt 7 ps 0.3 title "LRW counter", \
     't62_tile_s21.dat' index 5 using 1:2 with linespoints pt 7 ps 0.3 title "LRU counter"
unset logscale y
set ylabel 'hit rate (%)'
plot 't62_tile_s21.dat' index 0 using 1:3 with lines title "No eviction", \
     't62_tile_s21.dat' index 1 using 1:3 with lines title "Random", \
     't62_tile_s21.dat' index 2 using 1:3 with lines title "LRW frame", \
     't62_tile_s21.dat' index 3 using 1:3 with lines title "LRU frame", \
     't62_tile_s21.dat' index 4 using 1:3 with lines title "LRW counter", \
     't62_tile_s21.dat' index 5 using 1:3 with lines title "LRU counter"
unset multiplot

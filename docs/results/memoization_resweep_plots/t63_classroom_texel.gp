# Cache size, classroom, texel: frame time and hit rate over the camera path (make_tables).
set terminal pngcairo size 1400,500 noenhanced
set output 't63_classroom_texel.png'
set multiplot layout 1,2 title "Cache size, classroom, texel"
set xlabel 'camera (frame of the path)'
set key outside bottom center horizontal
set ylabel 'GPU ms/frame'
set logscale y
plot 't63_classroom_texel.dat' index 0 using 1:2 with linespoints pt 7 ps 0.3 title "2^18 texels", \
     't63_classroom_texel.dat' index 1 using 1:2 with linespoints pt 7 ps 0.3 title "2^19 texels", \
     't63_classroom_texel.dat' index 2 using 1:2 with linespoints pt 7 ps 0.3 title "2^20 texels", \
     't63_classroom_texel.dat' index 3 using 1:2 with linespoints pt 7 ps 0.3 title "2^21 texels", \
     't63_classroom_texel.dat' index 4 using 1:2 with linespoints pt 7 ps 0.3 title "2^22 texels", \
     't63_classroom_texel.dat' index 5 using 1:2 with linespoints pt 7 ps 0.3 title "2^23 texels"
unset logscale y
set ylabel 'hit rate (%)'
plot 't63_classroom_texel.dat' index 0 using 1:3 with lines title "2^18 texels", \
     't63_classroom_texel.dat' index 1 using 1:3 with lines title "2^19 texels", \
     't63_classroom_texel.dat' index 2 using 1:3 with lines title "2^20 texels", \
     't63_classroom_texel.dat' index 3 using 1:3 with lines title "2^21 texels", \
     't63_classroom_texel.dat' index 4 using 1:3 with lines title "2^22 texels", \
     't63_classroom_texel.dat' index 5 using 1:3 with lines title "2^23 texels"
unset multiplot

# AS memory and frame time over the city's camera path (make_culling_report).
set terminal pngcairo size 1400,500 noenhanced
set output 'culling.png'
set multiplot layout 1,2
set xlabel 'frame of the path'
set key outside bottom center horizontal
set ylabel 'BLAS + TLAS resident (MiB)'
plot 'culling.dat' index 0 using 1:2 with lines title 'none', \
     'culling.dat' index 1 using 1:2 with lines title 'frustum', \
     'culling.dat' index 2 using 1:2 with lines title 'lipac'
set ylabel 'trace + AS builds (GPU ms)'
plot 'culling.dat' index 0 using 1:4 with lines title 'none', \
     'culling.dat' index 1 using 1:4 with lines title 'frustum', \
     'culling.dat' index 2 using 1:4 with lines title 'lipac'
unset multiplot

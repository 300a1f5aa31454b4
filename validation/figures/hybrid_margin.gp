set terminal pngcairo size 900,900 font ',11' noenhanced
set output 'hybrid_margin.png'
set datafile separator ','
set multiplot layout 2,1 title 'The hybrid against pure DEM on its own grains, by DEM region margin (3 seeds; bars: standard error)'
set xlabel 'DEM region margin [m]'; set xrange [0.06:0.215]; set grid; set key bottom right
set ylabel 'hybrid - pure DEM [%]'
plot 3 with lines dt 2 lc rgb 'gray' notitle, -3 with lines dt 2 lc rgb 'gray' notitle, \
  'hybrid_margin.csv' every ::1 using ($1-0.002):2:3 with yerrorlines pt 7 lw 2 title 'wrap-around: sheet normal force 1-5 mm', \
  'hybrid_margin.csv' every ::1 using ($1+0.002):5:6 with yerrorlines pt 5 lw 2 title 'run-out: sheet normal force 1-5 mm', \
  'hybrid_margin.csv' every ::1 using 1:10:11 with yerrorbars pt 9 ps 1.5 lc rgb 'dark-green' title 'wrap-around: mean tension 10-60 mm', \
  'hybrid_margin.csv' every ::1 using 1:8:9 with yerrorbars pt 4 ps 1.5 title 'wrap-around: T_max'
set ylabel 'box grains / tank grains [%]'; set yrange [0:100]; set key top left
plot 'hybrid_margin.csv' every ::1 using 1:4 with linespoints pt 7 lw 2 title 'wrap-around (the bound on the saving: 100 / this)', \
  'hybrid_margin.csv' every ::1 using 1:7 with linespoints pt 5 lw 2 title 'run-out'
unset multiplot

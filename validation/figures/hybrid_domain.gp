set terminal pngcairo size 900,800 font ',11' noenhanced
set output 'hybrid_domain.png'
set datafile separator ','
set multiplot layout 2,1 title 'GT230 wrap-around H = 0.4 m, B = 0.25 m in soil masses of growing size (hybrid margin 0.15 m)'
set xlabel 'clusters pure DEM holds (the tank)'; set grid; set key top left; set xrange [0:*]
set ylabel 'whole run, wall time [s]'; set yrange [0:*]
plot 'hybrid_domain.csv' every ::1 using 1:3 with linespoints pt 7 lw 2 title 'pure DEM (median of its seeds)', \
  'hybrid_domain.csv' every ::1 using 1:4 with linespoints pt 5 lw 2 title 'hybrid (the same box in every tank; median of its seeds)'
set ylabel 'T_max [kN/m]'; set yrange [*:*]; set key top right
plot 'hybrid_domain.csv' every ::1 using 1:5 with linespoints pt 7 lw 2 title 'pure DEM (mean of its seeds)', \
  'hybrid_domain.csv' every ::1 using 1:6 with linespoints pt 5 lw 2 title 'hybrid (mean of its seeds)'
unset multiplot

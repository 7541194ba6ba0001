set terminal pngcairo size 720,450 font 'DejaVu Sans,10' noenhanced
set grid
set key outside right top noenhanced
set output 'thresholds.png'
set title "Each participant's threshold with its 95 % interval"
set ylabel 'threshold: difference in B (%) at 75 % correct'
set xrange [0.5:8.5]
set xtics ('S01' 1, 'S02' 2, 'S03' 3, 'S04' 4, 'S05' 5, 'S06' 6, 'S07' 7, 'S08' 8) rotate by -45
plot 'thresholds.dat' index 0 using 1:2:3:4 with yerrorbars pt 7 lc 1 title 'visual_only', \
     'thresholds.dat' index 1 using 1:2:3:4 with yerrorbars pt 7 lc 2 title 'tactile_only', \
     'thresholds.dat' index 2 using 1:2:3:4 with yerrorbars pt 7 lc 3 title 'both', \
     'thresholds.dat' index 3 using 1:2:3:4 with yerrorbars pt 7 lc 4 title 'none'

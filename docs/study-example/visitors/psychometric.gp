set terminal pngcairo size 720,450 font 'DejaVu Sans,10' noenhanced
set grid
set key outside right top noenhanced
set output 'psychometric.png'
set title 'Pooled psychometric functions (2AFC); points sized by trials, bars: 95 % intervals'
set xlabel 'difference in B (%)'
set ylabel 'proportion correct'
set yrange [0.3:1.05]
set xrange [0:32.5]
set arrow from graph 0, first 0.75 to graph 1, first 0.75 nohead dt 2 lc rgb '#888888'
plot 'psychometric.dat' index 0 using 1:2:(0.6 + 2.4 * sqrt($3 / 30.0)) with points pt 7 ps variable lc 1 title 'visual_only', \
     0.5 + 0.5*1/(1 + exp(-(2.76461822*(x - 15.1466624) + 0))) with lines lc 1 notitle, \
     '+' using (15.1466624):(0.75):(13.127751):(17.0020581) every ::0::0 with xerrorbars lc 1 pt 1 notitle, \
     'psychometric.dat' index 1 using 1:2:(0.6 + 2.4 * sqrt($3 / 30.0)) with points pt 7 ps variable lc 2 title 'tactile_only', \
     0.5 + 0.5*1/(1 + exp(-(0.361799085*(x - 14.0598656) + 0))) with lines lc 2 notitle, \
     '+' using (14.0598656):(0.75):(8.92102497):(15.9215941) every ::0::0 with xerrorbars lc 2 pt 1 notitle, \
     'psychometric.dat' index 2 using 1:2:(0.6 + 2.4 * sqrt($3 / 30.0)) with points pt 7 ps variable lc 3 title 'both', \
     0.5 + 0.5*1/(1 + exp(-(0.36379353*(x - 8.01786782) + 0))) with lines lc 3 notitle, \
     '+' using (8.01786782):(0.75):(0):(12.9582601) every ::0::0 with xerrorbars lc 3 pt 1 notitle

set terminal pngcairo size 720,450 font 'DejaVu Sans,10' noenhanced
set grid
set key outside right top noenhanced
set output 'response_times.png'
set title 'Response times per condition (50 ms bins)'
set xlabel 'response time (ms)'
set ylabel 'trials'
plot 'response_times.dat' index 0 using 1:2 with histeps lw 2 lc 1 title 'visual_only', \
     'response_times.dat' index 1 using 1:2 with histeps lw 2 lc 2 title 'tactile_only', \
     'response_times.dat' index 2 using 1:2 with histeps lw 2 lc 3 title 'both'

set terminal pngcairo size 640,400 font 'DejaVu Sans,9' noenhanced
set output 'prediction.png'
set title "Contact prediction at 100 Hz: contact → strike decided against speed error" noenhanced
set xlabel "contact → strike, median ms (faster ←)" noenhanced
set ylabel "speed error p99 % (strikes ≥ 1 m/s) (more exact ↓)" noenhanced
set key top right noenhanced
set grid
set offsets graph 0.08, graph 0.25, graph 0.1, graph 0.1
plot 'prediction.front.dat' using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front', \
     'prediction.dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'settings', \
     '' using 1:2:5 with labels offset 0,-1 font ',7' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2):4 with labels offset 0,1.2 tc rgb '#d62728' font ',8' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2) with points pt 6 ps 2.5 lc rgb '#d62728' title 'quality presets'

set terminal pngcairo size 640,400 font 'DejaVu Sans,9' noenhanced
set output 'modes.png'
set title "Modes per bar (glockenspiel, 4 modes, C6 at 2 m/s, 0.5 s)" noenhanced
set xlabel "ns per sample (faster ←)" noenhanced
set ylabel "max abs error vs all modes, long double (more exact ↓)" noenhanced
set key top right noenhanced
set grid
set offsets graph 0.08, graph 0.25, graph 0.1, graph 0.1
set logscale y
set format y '%.0e'
plot 'modes.front.dat' using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front', \
     'modes.dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'settings', \
     '' using 1:2:5 with labels offset 0,-1 font ',7' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2):4 with labels offset 0,1.2 tc rgb '#d62728' font ',8' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2) with points pt 6 ps 2.5 lc rgb '#d62728' title 'quality presets'

set terminal pngcairo size 640,400 font 'DejaVu Sans,9' noenhanced
set output 'pointer.png'
set title "Pointer filter (1€, min_cutoff 1 Hz, beta in 1/m): lag in strikes against still-cursor jitter" noenhanced
set xlabel "lag in strikes, ms (faster ←)" noenhanced
set ylabel "still jitter, mm (more exact ↓)" noenhanced
set key top right noenhanced
set grid
set offsets graph 0.08, graph 0.25, graph 0.1, graph 0.1
set logscale x
plot 'pointer.front.dat' using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front', \
     'pointer.dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'settings', \
     '' using 1:2:5 with labels offset 0,-1 font ',7' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2):4 with labels offset 0,1.2 tc rgb '#d62728' font ',8' notitle, \
     '' using 1:(strcol(4) eq "-" ? 1/0 : $2) with points pt 6 ps 2.5 lc rgb '#d62728' title 'quality presets'

# Redraw with: gnuplot elasticity.gp (in this directory)
if (!exists('output_directory')) output_directory = ''
set datafile separator ','
set terminal pngcairo size 900,500 noenhanced
set output output_directory.'elasticity.png'
set grid
set key outside right
set xrange [63.7:131.3]
set yrange [0:*]
set offsets 0, 0, graph 0.05, 0
set xlabel 'x [m]'
set ylabel 'elasticity [mm/N]'
set title 'fdm, N+1 = 780: static elasticity of span 2 (supports solid, droppers dashed)'
set arrow from 65, graph 0 to 65, graph 1 nohead lw 2 lc rgb 'black'
set label 'support' at 65, graph 1.03 center
set arrow from 130, graph 0 to 130, graph 1 nohead lw 2 lc rgb 'black'
set label 'support' at 130, graph 1.03 center
set arrow from 70.5, graph 0 to 70.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 79.5, graph 0 to 79.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 88.5, graph 0 to 88.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 97.5, graph 0 to 97.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 106.5, graph 0 to 106.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 115.5, graph 0 to 115.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
set arrow from 124.5, graph 0 to 124.5, graph 1 nohead dashtype 2 lc rgb '#d09030'
plot 'elasticity.csv' using 1:2 with linespoints pt 7 ps 0.6 title 'F = 100 N', 'elasticity.csv' using 1:3 with linespoints pt 7 ps 0.6 title 'F = 200 N'

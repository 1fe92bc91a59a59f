# Redraw with: gnuplot contact_force_over_x.gp (in this directory)
# Shaded: the evaluation window; dashed: the supports.
set datafile separator ','
set terminal pngcairo size 1200,500 noenhanced
set grid ytics
set key below horizontal
set offsets 0, 0, graph 0.08, graph 0.05
set xlabel 'x_p [m]'
set ylabel 'lambda_p [N]'
unset arrow
unset label
unset object
set output 'contact_force_over_x_pantograph_2.png'
set title 'test: contact force over x_p, pantograph 2, window x_p in [220, 330] m (spans 5-6)'
set xrange [100:300]
set arrow from first 110, graph 0 to first 110, graph 1 nohead dashtype 2 lc rgb '#707070'
set label 'span 3' at first 137.5, graph 0.96 center tc rgb '#505050'
set arrow from first 165, graph 0 to first 165, graph 1 nohead dashtype 2 lc rgb '#707070'
set label 'span 4' at first 192.5, graph 0.96 center tc rgb '#505050'
set arrow from first 220, graph 0 to first 220, graph 1 nohead dashtype 2 lc rgb '#707070'
set label 'span 5' at first 247.5, graph 0.96 center tc rgb '#505050'
set arrow from first 275, graph 0 to first 275, graph 1 nohead dashtype 2 lc rgb '#707070'
set object rectangle from first 220, graph 0 to first 300, graph 1 behind fillcolor rgb '#e4ecf8' fillstyle solid 1.0 noborder
plot 'contact_force.csv' using 5:6 with lines lc rgb '#a0a0a0' title 'lambda_p (raw)', 'contact_force.csv' using 5:7 with lines lw 1.5 lc rgb '#0060c0' title 'low pass 20 Hz (order 4)'

# Tread indentation (thesis 3.4): the rut and the force, from one run of
# configs/scenes/tread_indentation.textproto (2 mm particles, 75,000; this folder's
# CSVs are its terrain/rut_surface.csv and tyre/tread_block.csv), and the rut of the
# same run on the hard snow (--set coupling.terrain=../materials/snow_hard.textproto:
# rut_surface_hard.csv, tread_block_hard.csv).
#   cd docs/data/tread_indentation && gnuplot plot.gp
set terminal pngcairo size 1500,560 font ',11' noenhanced
set output '../../img/tread_indentation_rut.png'
set datafile separator ','
set multiplot layout 1,2 title 'Tread indentation (thesis 3.4): tread section pushed 8 mm into soft (Table 3.1) and hard (section 6.3) snow, 2 mm particles'
set grid
# (a) the snow's top along x in the cell row through y = 0, with the tread at its final depth.
set title '(a) rut: top particle centres along x (cell row at y = 0)'
set xlabel 'x [m]'
set ylabel 'z [mm]'
set xrange [-0.15:0.15]
set yrange [-12:4]
set key bottom right
# The tread's outline at the end: rib faces at -8 mm, grooves 10 mm deep, 10 mm wide.
set object 1 polygon from -0.094,-8 to -0.065,-8 to -0.065,2 to -0.055,2 to -0.055,-8 to -0.025,-8 to -0.025,2 \
  to -0.015,2 to -0.015,-8 to 0.015,-8 to 0.015,2 to 0.025,2 to 0.025,-8 to 0.055,-8 to 0.055,2 to 0.065,2 \
  to 0.065,-8 to 0.094,-8 to 0.094,4 to -0.094,4 to -0.094,-8 fs transparent solid 0.25 noborder fc rgb 'gray40'
near = 'abs($2) < 0.0005'
plot 'rut_surface.csv' every ::1 using 1:(abs($2) < 0.0005 ? ($3 + $4) * 1000 : 1/0) with lines lw 2 dt 2 title 'snow top at the start', \
     '' every ::1 using 1:(abs($2) < 0.0005 ? $3 * 1000 : 1/0) with linespoints lw 2 pt 7 ps 0.5 title 'soft snow (Table 3.1), end', \
     'rut_surface_hard.csv' every ::1 using 1:(abs($2) < 0.0005 ? $3 * 1000 : 1/0) with linespoints lw 2 pt 5 ps 0.5 title 'hard snow (6.3), end', \
     NaN with filledcurves fc rgb 'gray40' fs transparent solid 0.25 title 'tread section (grey)'
unset object 1
# (b) the snow's force on the tread section against the depth of its rib faces.
set title '(b) force of the snow on the tread section (0.01 m slice)'
set xlabel 'depth of the rib faces below the snow surface [mm]'
set ylabel 'force [N]'
set xrange [-1:9]
set yrange [0:*]
set key bottom right
plot 'tread_block.csv' every ::1 using ($3 * 1000):6 with lines lw 2 title 'soft snow: pushing at 0.5 m/s, then held at 8 mm', \
     'tread_block_hard.csv' every ::1 using ($3 * 1000):6 with lines lw 2 title 'hard snow'
unset multiplot

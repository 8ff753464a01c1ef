# The plate's resisting force against its depth, FE mesh and SPH particles, the
# same snows (docs/validation.md). Run from docs/data/plate_bearing:
#   gnuplot plot.gp   ->  ../../img/plate_bearing_fe_sph.png
set terminal pngcairo size 1000,650 font ",11"
set output "../../img/plate_bearing_fe_sph.png"
set datafile separator ","
set key bottom right font ",10"
set grid
set xlabel "plate displacement [m]"
set ylabel "force of the snow on the plate [N]"
set title "Plate pushed at 0.1 m/s, 20 mm, no quasi-static damping: Lagrangian mesh against SPH"
set xrange [0:0.3]
set yrange [0:2600]
plot 1867 with lines dt 2 lc rgb "black" title "laboratory load 1,867 N", \
     "fe_20mm_table31_pushed.csv" skip 2 using 1:2 with lines lw 3 lc rgb "#1f77b4" title "FE mesh, Table 3.1 snow (mesh inverts)", \
     "sph_20mm_table31_pushed.csv" skip 2 using 1:2 with lines lw 2 lc rgb "#1f77b4" dt 3 title "SPH, Table 3.1 snow", \
     "sph_20mm_table31_pushed_corrected.csv" skip 2 using 1:2 with lines lw 2 lc rgb "#1f77b4" dt 4 title "SPH, Table 3.1 snow, corrected gradient", \
     "fe_20mm_triaxial_pushed.csv" skip 2 using 1:2 with lines lw 3 lc rgb "#d62728" title "FE mesh, triaxial-matched snow (mesh inverts)", \
     "sph_20mm_triaxial_pushed.csv" skip 2 using 1:2 with lines lw 2 lc rgb "#d62728" dt 3 title "SPH, triaxial-matched snow", \
     "sph_20mm_triaxial_pushed_corrected.csv" skip 2 using 1:2 with lines lw 2 lc rgb "#d62728" dt 4 title "SPH, triaxial-matched snow, corrected gradient", \
     "sph_20mm_triaxial_pushed_av006.csv" skip 2 using 1:2 with lines lw 1 lc rgb "#ff9896" title "SPH, triaxial-matched snow, alpha 0.06, beta 1.2"

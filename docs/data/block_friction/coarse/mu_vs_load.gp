# Draws mu_vs_load.png from table.csv: gnuplot mu_vs_load.gp
set terminal pngcairo size 900,600 font ",11"
set output "mu_vs_load.png"
set datafile separator ","
set title "Friction coefficient F / P of the sliding block against load (thesis Table 4.3)"
set xlabel "load [N]"; set ylabel "friction coefficient F / P [-]"
set xrange [150:450]; set yrange [0:0.35]; set grid; set key top left
plot "table.csv" every ::1 using (strcol(2) eq "false" ? $1 : 1/0):4 with points ps 2 pt 7 title "ours, no sipes (coarse)", \
     "" every ::1 using (strcol(2) eq "true" ? $1 : 1/0):4 with points ps 2 pt 5 title "ours, three sipes (coarse)", \
     "" every ::1 using (strcol(2) eq "false" ? $1 : 1/0):8 with points ps 2 pt 6 title "thesis, no sipes", \
     "" every ::1 using (strcol(2) eq "true" ? $1 : 1/0):8 with points ps 2 pt 4 title "thesis, with sipes"

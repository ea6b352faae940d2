# Error (51) against total time (setup + solve), log-log, for one scene of a sweep CSV
# (bench/sweep.cpp). One curve per method and near rule: the series' own Pareto front (its
# cheapest runs for each error level); every run as a small point, grey crosses for runs whose
# solution is not within 5% of the discretization error (deviation from the dense exact solution
# above 5% of its error); the overall Pareto front of the faithful runs as black circles joined by
# a step line.
#   gnuplot -e "csv='bench/results/sweep.csv'; png='bench/results/pareto_cube.png'; scene='cube'" bench/plot_pareto.gp
# CSV columns: 1 scene, 2 n, 3 method, 4 near, 5 eta, 6 mu, 7 degree, 8 max_error, 9 setup_s,
# 10 solve_s, 11 iterations, 12 peak_rss_mb, 13 total_s, 14 deviation, 15 faithful (within 5% of
# the discretization error), 16 series_front, 17 pareto (both among faithful runs only)
if (!exists("csv")) csv = 'bench/results/sweep.csv'
if (!exists("png")) png = 'bench/results/pareto_cube.png'
if (!exists("scene")) scene = 'cube'
if (!exists("series")) series = '1 2 3 4 5 6 7 8'  # which series to draw (ids below)

set terminal pngcairo size 1100,760 enhanced font 'DejaVu Sans,11'
set output png
set datafile separator ','
set datafile missing ''
set key bottom left box opaque spacing 1.1 font ',10'
set logscale xy
set format x '10^{%L}'
set format y '%.0e'
set xlabel 'total time: setup + solve [s]'
set ylabel 'max_k |u(P_k) - u_n(P_k)|  (51)'
set title sprintf("panelrad, %s: error against run time (Neumann iteration, every run of the sweep)", scene)
set grid xtics ytics mxtics mytics lc rgb '#dddddd'

# series id: 1 dense exact, 2..4 dense quadrature mu=1..3, 5 fast exact, 6..8 fast quadrature mu=1..3
sid(m, r, mu) = (m eq 'dense' ? 0 : 4) + (r eq 'exact' ? 1 : 1 + mu)
mu_of(dummy) = strcol(4) eq 'exact' ? 0 : column(6)
pick(m, r, mu, front) = (strcol(1) eq scene && sid(strcol(3), strcol(4), mu_of(0)) == sid(m, r, mu) && (front == 0 || column(16) == 1))

array name[8] = ['dense exact', 'dense quadrature {/Symbol m}=1', 'dense quadrature {/Symbol m}=2', \
                 'dense quadrature {/Symbol m}=3', 'fast exact', 'fast quadrature {/Symbol m}=1', \
                 'fast quadrature {/Symbol m}=2', 'fast quadrature {/Symbol m}=3']
array mth[8] = ['dense', 'dense', 'dense', 'dense', 'fast', 'fast', 'fast', 'fast']
array rul[8] = ['exact', 'quadrature', 'quadrature', 'quadrature', 'exact', 'quadrature', 'quadrature', 'quadrature']
array muv[8] = [0, 1, 2, 3, 0, 1, 2, 3]
array col[8] = ['#1f77b4', '#17becf', '#9467bd', '#8c564b', '#d62728', '#ff7f0e', '#2ca02c', '#bcbd22']
array dt[8] = [2, 2, 2, 2, 1, 1, 1, 1]
array pt[8] = [5, 4, 6, 8, 7, 9, 11, 13]

set style data points
plot csv using ((strcol(1) eq scene && column(15) == 0) ? $13 : NaN):8 \
       with points pt 2 ps 0.6 lc rgb '#aaaaaa' title 'not within 5% of discretization error', \
     for [w in series] csv using ((pick(mth[int(w)], rul[int(w)], muv[int(w)], 0) && column(15) == 1) ? $13 : NaN):8 \
       with points pt pt[int(w)] ps 0.5 lc rgb col[int(w)] notitle, \
     for [w in series] csv using (pick(mth[int(w)], rul[int(w)], muv[int(w)], 1) ? $13 : NaN):8 smooth unique \
       with linespoints dt dt[int(w)] lw 2 pt pt[int(w)] ps 1.0 lc rgb col[int(w)] title name[int(w)], \
     csv using ((strcol(1) eq scene && column(17) == 1) ? $13 : NaN):8 smooth unique \
       with steps lw 1.5 lc rgb 'black' notitle, \
     csv using ((strcol(1) eq scene && column(17) == 1) ? $13 : NaN):8 \
       with points pt 6 ps 2.2 lw 2 lc rgb 'black' title 'Pareto front'

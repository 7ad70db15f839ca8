# SPDX-License-Identifier: GPL-3.0-or-later
# Renders docs/images/mesh-stern-slice-fin30.png from the segment files of scripts/grid_slice.py:
#   build/release/client/auvloop mesh --preset coarse --fin-deflection 30 --out /tmp/mesh30
#   scripts/grid_slice.py /tmp/mesh30 y 0.09 -0.76 -0.50 -0.09 0.09 /tmp/sl hull starboard_stern_plane background
#   gnuplot scripts/grid_slice.gp
set terminal pngcairo size 1400,1000 font "sans,12"
set output "docs/images/mesh-stern-slice-fin30.png"
set size ratio -1
set xrange [-0.76:-0.50]
set yrange [-0.09:0.09]
set xlabel "x (m, body frame, forward)"
set ylabel "z (m, down)"
set title "Coarse preset, slice y = 0.09 m through the starboard stern plane at 30 deg: background, hull and fin grids"
set key outside right
plot "/tmp/sl-background-0.dat" u 1:2:3:4 w vectors nohead lc rgb "#bbbbbb" lw 0.8 t "background active", \
     "/tmp/sl-background-1.dat" u 1:2:3:4 w vectors nohead lc rgb "#ff9900" lw 1.2 t "background fringe", \
     "/tmp/sl-hull-0.dat" u 1:2:3:4 w vectors nohead lc rgb "#3366cc" lw 0.8 t "hull active", \
     "/tmp/sl-starboard_stern_plane-0.dat" u 1:2:3:4 w vectors nohead lc rgb "#000000" lw 0.6 t "fin active", \
     "/tmp/sl-starboard_stern_plane-1.dat" u 1:2:3:4 w vectors nohead lc rgb "#dd0000" lw 0.8 t "fin fringe"

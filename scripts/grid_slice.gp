# SPDX-License-Identifier: GPL-3.0-or-later
# Renders a slice from the segment files of scripts/grid_slice.py (scripts/stern_slice.sh and
# scripts/root_gap_slice.sh run the whole chain). Variables: prefix (segment files), out (png),
# fin (the fin grid drawn), the window (xmin, xmax, ymin, ymax), ylabel_text and title_text.
if (!exists("prefix")) prefix = "/tmp/sl"
if (!exists("out")) out = "docs/images/mesh-stern-slice-fin30.png"
if (!exists("fin")) fin = "starboard_stern_plane"
if (!exists("xmin")) xmin = -0.76
if (!exists("xmax")) xmax = -0.50
if (!exists("ymin")) ymin = -0.09
if (!exists("ymax")) ymax = 0.09
if (!exists("ylabel_text")) ylabel_text = "z (m, down)"
if (!exists("title_text")) title_text = "Coarse preset, slice y = 0.09 m through the starboard stern plane at 30 deg: background, hull and fin grids (holes not drawn)"
set terminal pngcairo size 1400,1000 font "sans,12"
set output out
set size ratio -1
set xrange [xmin:xmax]
set yrange [ymin:ymax]
set xlabel "x (m, body frame, forward)"
set ylabel ylabel_text
set title title_text
set key outside right
f(grid, status) = sprintf("%s-%s-%d.dat", prefix, grid, status)
plot f("background", 0) u 1:2:3:4 w vectors nohead lc rgb "#bbbbbb" lw 0.8 t "background active", \
     f("background", 1) u 1:2:3:4 w vectors nohead lc rgb "#ff9900" lw 1.4 t "background fringe", \
     f("hull", 0) u 1:2:3:4 w vectors nohead lc rgb "#3366cc" lw 0.8 t "hull active", \
     f("hull", 1) u 1:2:3:4 w vectors nohead lc rgb "#00aa88" lw 1.2 t "hull fringe", \
     f(fin, 0) u 1:2:3:4 w vectors nohead lc rgb "#000000" lw 0.6 t "fin active", \
     f(fin, 1) u 1:2:3:4 w vectors nohead lc rgb "#dd0000" lw 0.8 t "fin fringe"

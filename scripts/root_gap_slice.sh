#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates docs/images/mesh-root-gap.png: the medium grid system with the fins undeflected, cut
# by the plane z = -0.002 m (just beside the mid-plane of the starboard stern plane), zoomed on
# the 3 mm gap between the fin's root face and the hull (grid_slice.py, grid_slice.gp).
# Usage: scripts/root_gap_slice.sh [BUILD_DIR] (default build/release).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/client/auvloop" mesh --preset medium --out "$work/mesh" >/dev/null
scripts/grid_slice.py "$work/mesh" z -0.002 -0.70 -0.60 0.025 0.075 "$work/sl" \
  hull starboard_stern_plane background
gnuplot -e "prefix='$work/sl'; out='docs/images/mesh-root-gap.png'; fin='starboard_stern_plane'; \
  xmin=-0.70; xmax=-0.60; ymin=0.025; ymax=0.075; ylabel_text='y (m, starboard)'; \
  title_text='Medium preset, slice z = -2 mm through the starboard stern plane at 0 deg: the root gap (holes not drawn)'" \
  scripts/grid_slice.gp
echo "wrote docs/images/mesh-root-gap.png"

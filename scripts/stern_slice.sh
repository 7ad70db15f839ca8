#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates docs/images/mesh-stern-slice-fin30.png: the coarse grid system with every fin at
# 30 deg, cut by the plane y = 0.09 m through the starboard stern plane (grid_slice.py), drawn by
# gnuplot (grid_slice.gp). Usage: scripts/stern_slice.sh [BUILD_DIR] (default build/release).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/client/auvloop" mesh --preset coarse --fin-deflection 30 --out "$work/mesh" >/dev/null
scripts/grid_slice.py "$work/mesh" y 0.09 -0.76 -0.50 -0.09 0.09 "$work/sl" \
  hull starboard_stern_plane background
gnuplot -e "prefix='$work/sl'; out='docs/images/mesh-stern-slice-fin30.png'" scripts/grid_slice.gp
echo "wrote docs/images/mesh-stern-slice-fin30.png"

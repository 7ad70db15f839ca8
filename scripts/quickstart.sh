#!/usr/bin/env bash
# The main job on the embedded defaults: installs what is missing, builds auvloop, then
#   1. describes the REMUS 100 preset and exports its surface,
#   2. runs the paper's heading step (0 -> 90 deg, Kp 1.5, Ki 0.6, Kd 1.0) on the derivative plant
#      (Prestero's model) and on its linearisation, and compares the two.
# Everything lands in out/quickstart/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh build/release -DCMAKE_BUILD_TYPE=Release -DAUVLOOP_BUILD_TESTS=OFF -DAUVLOOP_BUILD_BENCH=OFF
auvloop=build/release/client/auvloop
out=out/quickstart
mkdir -p "$out"

echo "== REMUS 100 geometry"
"$auvloop" geometry info
"$auvloop" geometry info --json > "$out/remus100-geometry.json"
"$auvloop" geometry export --out "$out/remus100.stl"

echo
echo "== The paper's heading step on the derivative plant"
"$auvloop" run examples/heading-step.toml --out "$out/heading-step-derivative"
echo
echo "== The same on the linearized plant"
# Linearised about straight running, REMUS is unstable in sway-yaw (a root near +1 /s); with the
# rudder saturated the paper's gains cannot hold it and the run stops as diverged (exit code 4),
# keeping the time series up to that point. See docs/derivative-plant.md.
"$auvloop" run examples/heading-step.toml --plant linearized --out "$out/heading-step-linearized" \
  || echo "(expected: the linearized plant diverges with these gains; its results are kept)"
echo
echo "== Comparison"
"$auvloop" compare "$out/heading-step-derivative" "$out/heading-step-linearized" \
  --label derivative --label linearized --out "$out/heading-step-comparison"
echo
echo "quickstart: results in $out/ (plots: $out/heading-step-comparison/*.png)"

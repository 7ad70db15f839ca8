#!/usr/bin/env bash
# The main job on the embedded defaults: installs what is missing, builds auvloop, then
#   1. describes the REMUS 100 preset and exports its surface,
#   2. runs the paper's heading step (0 -> 90 deg, Kp 1.5, Ki 0.6, Kd 1.0) on the derivative plant
#      (Prestero's model) and on its linearisation, and compares the two,
#   3. tunes the PID gains as the paper does (Kriging, 20 LHS points, EI + MSP) through the
#      scheduler daemon, which this script starts and stops itself.
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
echo "== The first second of the heading step on the CFD plant (coarse mesh, SST; docs/cfd-plant.md)"
# The flow around the vehicle solved every 10 ms step, the body moving with it (about two
# minutes). The whole 30 s manoeuvre: examples/cfd-heading-step.toml (about 70 minutes).
"$auvloop" run examples/cfd-quickstart.toml --out "$out/cfd-quickstart"
echo
echo "== The paper's PID tuning through the scheduler daemon (docs/scheduler.md)"
# A private daemon: its own state directory and socket, so a daemon of yours is not disturbed.
daemon=(--state-dir "$out/daemon-state" --socket "${TMPDIR:-/tmp}/auvloop-quickstart-$(id -u).sock")
"$auvloop" daemon start "${daemon[@]}"
trap '"$auvloop" daemon stop "${daemon[@]}" >/dev/null 2>&1 || true' EXIT
"$auvloop" optimize examples/pid-optimization.toml --daemon --wait "${daemon[@]}"
echo
"$auvloop" results list --limit 5 "${daemon[@]}"
echo
echo "quickstart: results in $out/ (plots: $out/heading-step-comparison/*.png; the daemon's"
echo "cache: $out/daemon-state/cache/)"

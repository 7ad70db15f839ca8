#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The CFD plant's speed on a whole manoeuvre (issue 18, "Speed"): examples/cfd-heading-step.toml
# (the paper's 0 -> 90 deg heading step, coarse preset, 30 s of 10 ms steps) run by `auvloop run`
# as a user runs it, timed as a whole process by GNU time. Reported:
#   - the wall time of the whole command, of the straight run before t = 0 (computed afresh: the
#     straight-run store is a new, empty directory) and of the manoeuvre alone (the first progress
#     line at t >= 0 to the end), and seconds per step of each;
#   - the plant's wall-clock split (fins, coupling, momentum, pressure, turbulence, the rest; of
#     which overset), as auvloop run prints it;
#   - the peak memory (GNU time's maximum resident set size);
#   - the solver's work per step from the run's timeseries.csv (outer iterations, Krylov
#     iterations of pressure, momentum and k-omega, largest Courant number);
#   - a baseline measured in the same run, before and after the case: a 20-step straight run of
#     the same plant, towed (cfd_plant_run --time 0.2: ten 2 ms steps, then 10 ms ones, relaxed
#     as the case file's defaults); the case's
#     seconds per step as a ratio to the baseline's compare across machines and loads better than
#     the minutes do.
# The load average is printed before and after: the figures mean something only on an otherwise
# idle machine (load about 2.0 from this run on 2 cores).
#   bench/cfd_heading_step.sh [BUILD_DIR] [DURATION_S] [OUT_DIR]
# DURATION_S (default 30) cuts the case short (a quicker look at the cost of the first seconds,
# where the rudder moves); OUT_DIR (default a temporary directory) keeps the run directory and the
# logs.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build/release}")
duration=${2:-30}
out=${3:-$(mktemp -d)}
mkdir -p "$out"
out=$(realpath "$out")
auvloop="$build/client/auvloop"
baseline="$build/bench/cfd_plant_run"
for exe in "$auvloop" "$baseline"; do
  [[ -x $exe ]] || { echo "missing $exe (build with -DAUVLOOP_BUILD_BENCH=ON)" >&2; exit 2; }
done
[[ -x /usr/bin/time ]] || { echo "missing /usr/bin/time (apt-get install time)" >&2; exit 2; }

echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)   cores: $(nproc)   $(date -u +%FT%TZ)"
run_baseline() {  # seconds per step of the 20-step straight run (the last ten steps' mean)
  "$baseline" --time 0.2 --start-steps 10 --free none --relax-u 0.7 --relax-p 0.3 \
    --intermediate-tolerance 1e-4 --csv "$out/baseline-$1.csv" >/dev/null
  python3 - "$out/baseline-$1.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
tail = [float(r["seconds"]) for r in rows[-10:]]
print(f"{sum(tail) / len(tail):.4f}")
EOF
}
b0=$(run_baseline before)
echo "baseline (20-step straight run, mean of the last 10 steps): $b0 s/step"

sed -e "s/^duration = 30 .*/duration = $duration/" examples/cfd-heading-step.toml >"$out/case.toml"
export AUVLOOP_STATE_DIR="$out/state"  # empty: the straight run is computed and timed
rm -rf "$AUVLOOP_STATE_DIR"
/usr/bin/time -v -o "$out/time.txt" "$auvloop" run "$out/case.toml" -o "$out/run" >"$out/run.log" 2>&1
b1=$(run_baseline after)
echo "baseline after the case: $b1 s/step"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$out" "$duration" "$b0" "$b1" <<'EOF'
import csv, re, statistics, sys
out, duration, b0, b1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
timing = open(f"{out}/time.txt").read()
wall = timing.split("Elapsed (wall clock) time (h:mm:ss or m:ss):")[1].split()[0]
parts = [float(x) for x in wall.split(":")]
seconds = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", timing).group(1))
log = open(f"{out}/run.log").read()
progress = [(float(a), float(b)) for a, b in
            re.findall(r"t = (-?[\d.]+) / [\d.]+ s after (\d+) s", log)]
start = next(((t, w) for t, w in progress if t >= 0), None)
steps = round(duration / 0.01)
print(f"whole command: {seconds:.0f} s ({seconds / 60:.1f} min), peak memory {rss / 1024:.0f} MiB")
if start:
    manoeuvre = seconds - start[1]
    done = steps - round(start[0] / 0.01)
    print(f"straight run (to t = {start[0]:.2f} s): {start[1]:.0f} s; manoeuvre from there: "
          f"{manoeuvre:.0f} s for {done} steps, {manoeuvre / done:.3f} s/step, "
          f"{manoeuvre / done / ((b0 + b1) / 2):.2f} times the baseline's step")
split = re.search(r"the plant's .*", log)
print(split.group(0) if split else "no wall-clock split in the log")
rows = list(csv.reader(open(f"{out}/run/timeseries.csv")))
head = [h.split(" [")[0] for h in rows[0]]
data = [r for r in rows[1:] if r[head.index("solver.outer")] != ""]
for name in ["solver.outer", "solver.p_iterations", "solver.U_iterations",
             "solver.komega_iterations", "solver.courant"]:
    v = [float(r[head.index(name)]) for r in data]
    print(f"  {name:26s} mean {statistics.mean(v):8.2f}  max {max(v):8.2f}")
print(open(f"{out}/run/metrics.json").read().strip()[:2000])
EOF
echo "run directory and logs: $out"

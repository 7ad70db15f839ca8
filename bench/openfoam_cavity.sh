#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Peer comparison: OpenFOAM v1912 (Debian package openfoam) and auvloop's bench_cfd on the same 3D
# lid-driven cavity (unit cube, lid 1 m/s, nu = 0.01, N^3 uniform cells, dt = 1 / N for Courant 1
# at the lid, 2 pressure correctors, p to 1e-6 and U to 1e-5). Every figure is seconds per time step from the
# second step on (start-up and the first step excluded: icoFoam's and pimpleFoam's from the
# differences of their ExecutionTime lines, auvloop's solver time as bench_cfd reports it), and
# each is printed as a ratio to icoFoam with GAMG on 1 process, measured first in the same run
# (above 1: slower than it). Lines, by key (CAVITY_LINES picks them):
#   ico-gamg-1    icoFoam, p by GAMG (Gauss-Seidel smoothing), 1 process: the baseline, always run
#   ico-dic-1     icoFoam, p by PCG with DIC, 1 process
#   ico-gamg-2    icoFoam -parallel, GAMG, 2 processes (decomposePar, mpirun -np 2)
#   pimple-gamg-1 pimpleFoam, GAMG, PIMPLE { nOuterCorrectors 1; nCorrectors 2;
#                 momentumPredictor yes; } (PISO mode), laminar, 1 process
#   pimple-gamg-2 the same pimpleFoam -parallel on 2 processes
#   auv-dic-1     auvloop bench_cfd --pressure cg-dic, 1 thread
#   auv-amg-1     auvloop bench_cfd --pressure cg-amg, 1 thread
#   auv-amg-2     auvloop bench_cfd --pressure cg-amg --threads 2
# Like for like: Euler in time, linear-upwind convection of U with a least-squares gradient of U,
# orthogonal Laplacians, PISO with 2 correctors (one outer iteration), p to 1e-6 with relTol 0
# (pFinal too), DIC-preconditioned CG against cg-dic and each code's own multigrid (GAMG, cg-amg)
# against each other; the parallel pairs are OpenFOAM on 2 MPI processes against auvloop on 2
# threads of one process. Both codes stop their solvers on OpenFOAM's normalised residual (auvloop's
# --residual-norm normalised), p at 1e-6 and U at 1e-5. Differences: U by OpenFOAM's symmetric
# Gauss-Seidel smoothSolver, auvloop's by its own momentum solver (bench_cfd's header line,
# printed below, names it); pimpleFoam adds
# the explicit div(nuEff dev2(T(grad U))) term of its laminar (Stokes) model and the PIMPLE
# bookkeeping around the same PISO loop; ExecutionTime is the CPU time of the (master) process in
# 0.01 s ticks (ClockTime, its wall clock, counts whole seconds), so it leaves out the time spent
# waiting for a core on a loaded machine, bench_cfd's figure is wall-clock time; the 2-process runs split the cube by decomposePar into
# two 2 x 1 x 1 halves (method simple: Debian's v1912 ships only the stub of scotchDecomp, so
# scotch, the cut a graph partitioner would also make on a cube, fails there) and pay MPI halo
# exchanges and global reductions, auvloop's 2 threads share one address space.
#   bench/openfoam_cavity.sh [BUILD_DIR] [N] [STEPS]
# Environment:
#   CAVITY_LINES      comma- or space-separated keys from the list above, or "all" (the default);
#                     ico-gamg-1 is run whatever it says, as the baseline
#   CAVITY_KEEP=1     keep the OpenFOAM case directory (logs) and print where it is
# The machine load (uptime's load average) is printed at the start and at the end: the figures
# are only comparable when it stayed low and steady.
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help ]]; then
  sed -n '3,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  exit 0
fi
build=${1:-build/release}
n=${2:-64}
steps=${3:-5}
lines=${CAVITY_LINES:-all}
bashrc=/usr/share/openfoam/etc/bashrc
all_keys="ico-gamg-1 ico-dic-1 ico-gamg-2 pimple-gamg-1 pimple-gamg-2 auv-dic-1 auv-amg-1 auv-amg-2"
[[ $n =~ ^[0-9]+$ && $n -ge 2 ]] || { echo "N must be an integer >= 2, got $n" >&2; exit 2; }
[[ $steps =~ ^[0-9]+$ && $steps -ge 2 ]] || {
  echo "STEPS must be an integer >= 2 (the first step is not timed), got $steps" >&2; exit 2; }
[[ -f $bashrc ]] || {
  echo "OpenFOAM not found (AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh)" >&2; exit 1; }
# The selected keys, in the order of all_keys, the baseline first.
[[ $lines == all ]] && lines=$all_keys
selected="ico-gamg-1"
for key in ${lines//,/ }; do
  [[ " $all_keys " == *" $key "* ]] || {
    echo "unknown line $key in CAVITY_LINES (known: $all_keys)" >&2; exit 2; }
done
for key in $all_keys; do
  [[ $key != ico-gamg-1 && " ${lines//,/ } " == *" $key "* ]] && selected+=" $key"
done
# mpirun: Debian's Open MPI (4.1) refuses to start as root without --allow-run-as-root, and
# --oversubscribe lets -np 2 start where it counts fewer slots than 2 (a cgroup-limited machine).
mpirun_flags="--oversubscribe"
[[ $(id -u) == 0 ]] && mpirun_flags="--allow-run-as-root $mpirun_flags"

case=$(mktemp -d)
if [[ ${CAVITY_KEEP:-0} == 1 ]]; then
  trap 'echo "case directory kept: $case"' EXIT
else
  trap 'rm -rf "$case"' EXIT
fi
dt=$(python3 -c "print('%.6g' % (1.0 / $n))")
end=$(python3 -c "print($steps / $n)")
mkdir -p "$case/system" "$case/constant" "$case/0"
header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }
{ header dictionary blockMeshDict
  cat <<EOD
scale 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) ($n $n $n) simpleGrading (1 1 1));
boundary (
  lid { type wall; faces ((3 7 6 2)); }
  walls { type wall; faces ((0 4 7 3) (2 6 5 1) (1 5 4 0) (0 3 2 1) (4 5 6 7)); }
);
EOD
} > "$case/system/blockMeshDict"
# The controlDict for application $1.
control() {
  { header dictionary controlDict
    echo "application $1; startFrom startTime; startTime 0; stopAt endTime; endTime $end;"
    echo "deltaT $dt; writeControl timeStep; writeInterval 100000; writeFormat binary;"
    echo "runTimeModifiable false;"
  } > "$case/system/controlDict"
}
control icoFoam
{ header dictionary fvSchemes
  echo "ddtSchemes { default Euler; } gradSchemes { default Gauss linear; grad(U) leastSquares; }"
  echo "divSchemes { default none; div(phi,U) Gauss linearUpwind grad(U);"
  echo "             div((nuEff*dev2(T(grad(U))))) Gauss linear; }"
  echo "laplacianSchemes { default Gauss linear orthogonal; } interpolationSchemes { default linear; }"
  echo "snGradSchemes { default orthogonal; }"
} > "$case/system/fvSchemes"
decomposition="simple 2x1x1"
{ header dictionary decomposeParDict
  echo "numberOfSubdomains 2; method simple; simpleCoeffs { n (2 1 1); delta 0.001; }"
} > "$case/system/decomposeParDict"
# icoFoam reads nu only; pimpleFoam's singlePhaseTransportModel also the model, and its
# turbulence library constant/turbulenceProperties (v1912; momentumTransport is later .org).
{ header dictionary transportProperties; echo "transportModel Newtonian; nu 0.01;"; } \
  > "$case/constant/transportProperties"
{ header dictionary turbulenceProperties; echo "simulationType laminar;"; } \
  > "$case/constant/turbulenceProperties"
{ header volVectorField U
  echo "dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);"
  echo "boundaryField { lid { type fixedValue; value uniform (1 0 0); } walls { type noSlip; } }"
} > "$case/0/U"
{ header volScalarField p
  echo "dimensions [0 2 -2 0 0 0 0]; internalField uniform 0;"
  echo "boundaryField { lid { type zeroGradient; } walls { type zeroGradient; } }"
} > "$case/0/p"
foam() { bash -c "set +u; source $bashrc >/dev/null 2>&1; cd '$case' && $1"; }
foam "blockMesh > log.blockMesh 2>&1" || { tail -n 20 "$case/log.blockMesh" >&2; exit 1; }
parallel=0
[[ " $selected " == *" ico-gamg-2 "* || " $selected " == *" pimple-gamg-2 "* ]] && parallel=1
if [[ $parallel == 1 ]]; then  # once: the fields of 0/ are the same for every run
  foam "decomposePar -force > log.decomposePar 2>&1" ||
    { tail -n 20 "$case/log.decomposePar" >&2; exit 1; }
fi

# Seconds per step of OpenFOAM's application $1 (icoFoam or pimpleFoam) on $2 processes with the
# p solver given as fvSolution entries ($3). Prints the figure, or fails with the log's tail.
foam_step() {
  local app=$1 np=$2 psolver=$3 log="$case/log.$1.$2.$4"
  control "$app"
  { header dictionary fvSolution
    echo "solvers { p { $psolver tolerance 1e-06; relTol 0; }"
    echo "          pFinal { \$p; relTol 0; }"
    echo "          U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-05; relTol 0; }"
    echo "          UFinal { \$U; relTol 0; } }"
    echo "PISO { nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }"
    echo "PIMPLE { nOuterCorrectors 1; nCorrectors 2; nNonOrthogonalCorrectors 0;"
    echo "         momentumPredictor yes; pRefCell 0; pRefValue 0; }"
  } > "$case/system/fvSolution"
  rm -rf "$case"/[1-9]* "$case"/0.[0-9]* "$case"/processor*/[1-9]* "$case"/processor*/0.[0-9]*
  if [[ $np == 1 ]]; then
    foam "$app > '$log' 2>&1" || { tail -n 20 "$log" >&2; return 1; }
  else
    # shellcheck disable=SC2086  # the flags are words
    foam "mpirun $mpirun_flags -np $np $app -parallel > '$log' 2>&1" ||
      { tail -n 20 "$log" >&2; return 1; }
  fi
  grep '^ExecutionTime' "$log" | awk '{print $3}' | python3 -c "
import sys; t = [float(x) for x in sys.stdin.read().split()]
assert len(t) == $steps, 'expected $steps ExecutionTime lines, got %d' % len(t)
print('%.6g' % ((t[-1] - t[0]) / (len(t) - 1)))" || { tail -n 20 "$log" >&2; return 1; }
}
# Seconds per auvloop step with the pressure solver $1 on $2 threads. bench_cfd prints a line with
# "s/step VALUE" (and, when it has them, "us/cell/step VALUE" and "cells=CELLS", from which the
# figure is taken to more digits); its first line, the set-up, is kept in $case/log.auv.*.
ours_step() {
  local log="$case/log.auv.$1.$2"
  [[ -x $build/bench/bench_cfd ]] || { echo "$build/bench/bench_cfd not found" >&2; return 1; }
  "$build/bench/bench_cfd" --n "$n" --steps "$steps" --threads "$2" --time euler \
    --convection linear-upwind --pressure "$1" --residual-norm normalised --tolerance 1e-6 \
    --momentum-tolerance 1e-5 > "$log" 2>&1 || { tail -n 20 "$log" >&2; return 1; }
  awk '{ for (i = 1; i < NF; ++i) {
           if ($i ~ /^cells=/) { cells = substr($i, 7) }
           if ($i == "us/cell/step") us = $(i + 1)
           if ($i == "s/step") s = $(i + 1) } }
       END { if (us != "" && cells != "") printf "%.6g\n", us * cells / 1e6
             else if (s != "") print s
             else exit 1 }' "$log" || { echo "no s/step in bench_cfd's output" >&2; return 1; }
}
# Label and measurement of each key.
label() {
  case $1 in
    ico-gamg-1) echo "icoFoam GAMG 1 process" ;;
    ico-dic-1) echo "icoFoam PCG-DIC 1 process" ;;
    ico-gamg-2) echo "icoFoam GAMG 2 processes ($decomposition)" ;;
    pimple-gamg-1) echo "pimpleFoam GAMG 1 process" ;;
    pimple-gamg-2) echo "pimpleFoam GAMG 2 processes ($decomposition)" ;;
    auv-dic-1) echo "auvloop cg-dic 1 thread" ;;
    auv-amg-1) echo "auvloop cg-amg 1 thread" ;;
    auv-amg-2) echo "auvloop cg-amg 2 threads" ;;
  esac
}
gamg="solver GAMG; smoother GaussSeidel;"
dic="solver PCG; preconditioner DIC;"
measure() {
  case $1 in
    ico-gamg-1) foam_step icoFoam 1 "$gamg" gamg ;;
    ico-dic-1) foam_step icoFoam 1 "$dic" dic ;;
    ico-gamg-2) foam_step icoFoam 2 "$gamg" gamg ;;
    pimple-gamg-1) foam_step pimpleFoam 1 "$gamg" gamg ;;
    pimple-gamg-2) foam_step pimpleFoam 2 "$gamg" gamg ;;
    auv-dic-1) ours_step cg-dic 1 ;;
    auv-amg-1) ours_step cg-amg 1 ;;
    auv-amg-2) ours_step cg-amg 2 ;;
  esac
}

echo "cavity ${n}^3, $steps steps (s/step from the 2nd on), dt $dt, Euler + linear upwind"
# shellcheck disable=SC2016  # expanded by the shell that sourced OpenFOAM's bashrc
echo "(least-squares grad U), PISO 2 correctors, p to 1e-6, U to 1e-5 (normalised residuals); OpenFOAM $(foam 'echo $WM_PROJECT_VERSION')"
[[ $parallel == 1 ]] && echo "OpenFOAM on 2 processes: decomposePar, method $decomposition;" \
  "mpirun $mpirun_flags -np 2 APP -parallel"
echo "load average at start: $(uptime | sed 's/.*load average: //')"
base=""
rows=()
failed=0
for key in $selected; do
  if s=$(measure "$key"); then
    [[ $key == ico-gamg-1 ]] && base=$s
    if [[ -n $base ]] && python3 -c "import sys; sys.exit(not $base > 0)"; then
      ratio=$(python3 -c "print('%.2f' % ($s / $base))")
    else
      ratio="-"
    fi
  else
    echo "  ($key failed: see above)" >&2
    s="failed"
    failed=$((failed + 1))
    ratio="-"
  fi
  [[ $s != failed ]] && s=$(python3 -c "print('%.4g' % $s)")
  rows+=("$(printf '%-44s %10s %8s' "$(label "$key")" "$s" "$ratio")")
done
echo "load average at end:   $(uptime | sed 's/.*load average: //')"
for f in "$case"/log.auv.*; do  # auvloop's set-up, as bench_cfd states it
  [[ -f $f ]] && echo "auvloop set-up: $(head -n 1 "$f")" && break
done
printf '%-44s %10s %8s\n' "label" "s/step" "ratio-to-icoFoam-GAMG-1"
printf '%s\n' "${rows[@]}"
[[ -n $base ]] && python3 -c "import sys; sys.exit(not ($steps - 1) * $base < 1)" &&
  echo "(OpenFOAM's ExecutionTime counts in 0.01 s: its figures here are rough; take more steps or N)"
exit $((failed > 0))  # 1 if a line failed (its log's tail went to stderr)

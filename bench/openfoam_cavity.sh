#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Peer comparison: OpenFOAM's icoFoam (Debian package openfoam, v1912) and auvloop's bench_cfd on
# the same 3D lid-driven cavity (unit cube, lid 1 m/s, nu = 0.01, N^3 uniform cells, dt for
# Courant 1 at the lid, 2 pressure correctors, p to 1e-6), both single-threaded; prints the
# seconds per time step of each (from the second step on for icoFoam, so start-up is excluded;
# auvloop's solver time only) and the ratio, for two pairs of pressure solvers: DIC-preconditioned
# CG on both sides, then each code's multigrid (OpenFOAM's GAMG with Gauss-Seidel smoothing,
# auvloop's cg-amg, the default for 3D grids).
# Like for like: both Euler in time, linear-upwind convection with a least-squares gradient of U,
# PISO (one outer iteration). Remaining differences: OpenFOAM's p tolerance is on its normalised
# residual, auvloop's on |r| / |b|; U by symmetric Gauss-Seidel (OpenFOAM) and Jacobi-BiCGSTAB
# (auvloop).
#   bench/openfoam_cavity.sh [BUILD_DIR] [N] [STEPS]
set -euo pipefail
build=${1:-build/release}
n=${2:-64}
steps=${3:-5}
bashrc=/usr/share/openfoam/etc/bashrc
[[ -f $bashrc ]] || { echo "OpenFOAM not found (AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh)"; exit 1; }
case=$(mktemp -d)
trap 'rm -rf "$case"' EXIT
dt=$(python3 -c "print(1.0 / $n)")
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
{ header dictionary controlDict
  echo "application icoFoam; startFrom startTime; startTime 0; stopAt endTime; endTime $end;"
  echo "deltaT $dt; writeControl timeStep; writeInterval 100000; writeFormat binary; runTimeModifiable false;"
} > "$case/system/controlDict"
{ header dictionary fvSchemes
  echo "ddtSchemes { default Euler; } gradSchemes { default Gauss linear; grad(U) leastSquares; }"
  echo "divSchemes { default none; div(phi,U) Gauss linearUpwind grad(U); }"
  echo "laplacianSchemes { default Gauss linear orthogonal; } interpolationSchemes { default linear; }"
  echo "snGradSchemes { default orthogonal; }"
} > "$case/system/fvSchemes"
{ header dictionary transportProperties; echo "nu 0.01;"; } > "$case/constant/transportProperties"
{ header volVectorField U
  echo "dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);"
  echo "boundaryField { lid { type fixedValue; value uniform (1 0 0); } walls { type noSlip; } }"
} > "$case/0/U"
{ header volScalarField p
  echo "dimensions [0 2 -2 0 0 0 0]; internalField uniform 0;"
  echo "boundaryField { lid { type zeroGradient; } walls { type zeroGradient; } }"
} > "$case/0/p"
# Seconds per icoFoam time step with the p solver given as fvSolution entries ($1).
foam_step() {
  { header dictionary fvSolution
    echo "solvers { p { $1 tolerance 1e-06; relTol 0; }"
    echo "          pFinal { \$p; relTol 0; }"
    echo "          U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-05; relTol 0; } }"
    echo "PISO { nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }"
  } > "$case/system/fvSolution"
  rm -rf "$case"/[1-9]* "$case"/0.[0-9]*
  bash -c "set +u; source $bashrc >/dev/null 2>&1; cd '$case' && blockMesh > log.blockMesh && icoFoam > log.icoFoam"
  grep '^ExecutionTime' "$case/log.icoFoam" | awk '{print $3}' | python3 -c "
import sys; t = [float(x) for x in sys.stdin.read().split()]
print((t[-1] - t[0]) / (len(t) - 1))"
}
# Seconds per auvloop time step with the pressure solver $1.
ours_step() {
  "$build/bench/bench_cfd" --n "$n" --steps "$steps" --threads 1 --time euler \
    --convection linear-upwind --pressure "$1" | awk '/s\/step/ {print $NF}'
}
echo "cavity ${n}^3, $steps steps, 1 thread, Euler + linear upwind (least-squares grad U) on both sides"
for pair in "PCG DIC|solver PCG; preconditioner DIC;|cg-dic" \
            "GAMG / cg-amg|solver GAMG; smoother GaussSeidel;|cg-amg"; do
  IFS='|' read -r label foam_p ours_p <<< "$pair"
  foam=$(foam_step "$foam_p")
  ours=$(ours_step "$ours_p")
  echo "  p by $label: icoFoam s/step $foam, auvloop s/step $ours, auvloop / icoFoam = $(python3 -c "print('%.2f' % ($ours / $foam))")"
done

#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Peer comparison: OpenFOAM (Debian package openfoam, v1912) on the very grid auvloop's
# Schaefer-Turek validation uses (mesher::cylinder_channel with m cells per side of the O-grid's
# box, RADIAL * m radial cells graded RADIAL_RATIO : 1 (environment; default 0.5 and 4, the 2D-1
# grid; 1 and 8 for the 2D-2 grid), DOWN * m downstream cells, written by
# bench/schaefer_turek_study --polymesh).
# Case as validation-data.md section 2: nu = 1e-3, rho = 1, inflow the face average of the
# parabola 4 Um y (H - y) / H^2 (as auvloop imposes it: 4 Um (y (H - y) - h^2 / 12) / H^2), no-slip
# walls and cylinder, p = 0 and zero-gradient U at the outlet, zero-gradient p elsewhere.
# Schemes as auvloop's: least-squares gradients, linear-upwind convection (DIV overrides it),
# Gauss linear corrected Laplacians.
#   2d1: Um = 0.3, simpleFoam (SIMPLEC) to the steady state; prints cD, cL with their pressure and
#        viscous parts from the forces function object (wall value of p = wall-cell value, du/dn
#        one-sided; auvloop's fv::patch_force is the same evaluation) and from the two-cell wall
#        stencil (p and du/dn from the wall cell and the next one: converges at first order from
#        above, docs/cfd.md), and dp = p(0.15, 0.2) - p(0.25, 0.2) (wall-extrapolated).
#   2d2: Um = 1.5, pimpleFoam, backward, dt = 0.002, 2 outer / 2 pressure / 1 non-orthogonal
#        correctors, to END s (default 6); the cylinder spins at Ubar / 2 for the first 0.2 s (as
#        auvloop's kick); prints St, cD max / mean / min, cL max / min over the last 3 periods
#        (forces function object), then both evaluations on the fields written over the last 0.4 s.
# auvloop's side on the same grid: build/bench/schaefer_turek_study with the same grid options
# (auvloop's validation convection is van_leer_skew, closest to OpenFOAM's vanLeerV; pass
# --convection linear-upwind there for the like of "Gauss linearUpwind grad(U)").
#   bench/openfoam_cylinder.sh BUILD_DIR 2d1|2d2 M [DOWN] [DIV] [CASE_DIR]
# DOWN defaults to 2; DIV to "Gauss linearUpwind grad(U)"; CASE_DIR to a temporary directory
# (removed at the end). END (environment) sets 2d2's end time.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?build dir}
kind=${2:?2d1 or 2d2}
m=${3:?m}
down=${4:-2}
div=${5:-Gauss linearUpwind grad(U)}
case=${6:-}
end=${END:-6}
bashrc=/usr/share/openfoam/etc/bashrc
[[ -f $bashrc ]] || { echo "OpenFOAM not found (AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh)"; exit 1; }
if [[ -z $case ]]; then
  case=$(mktemp -d)
  trap 'rm -rf "$case"' EXIT
fi
post() { python3 "$here/openfoam_cylinder.py" "$@"; }
foam() { bash -c "set +u; source $bashrc >/dev/null 2>&1; cd '$case' && $*"; }

rm -rf "$case" && mkdir -p "$case/system" "$case/constant" "$case/0"
"$build/bench/schaefer_turek_study" --m "$m" --radial "${RADIAL:-0.5}" \
  --radial-ratio "${RADIAL_RATIO:-4}" --downstream "$down" --polymesh "$case" > /dev/null
tz=$(post thickness "$case")
if [[ $kind == 2d1 ]]; then um=0.3; else um=1.5; fi
ubar=$(python3 -c "print(2 * $um / 3)")

header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }
{ header dictionary transportProperties; echo "transportModel Newtonian; nu 1e-3;"; } \
  > "$case/constant/transportProperties"
{ header dictionary turbulenceProperties; echo "simulationType laminar;"; } \
  > "$case/constant/turbulenceProperties"
cyl_u="type noSlip;"
[[ $kind == 2d2 ]] && cyl_u="type rotatingWallVelocity; origin (0.2 0.2 0); axis (0 0 1); omega $(python3 -c "print(0.5 * $ubar / 0.05)"); value uniform (0 0 0);"
{ header volVectorField U
  echo "dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);"
  echo "boundaryField {"
  echo "  inlet { type fixedValue; value $(post inlet "$case" "$um"); }"
  echo "  outlet { type zeroGradient; } walls { type noSlip; } cylinder { $cyl_u }"
  echo "  front { type empty; } back { type empty; } }"
} > "$case/0/U"
{ header volScalarField p
  echo "dimensions [0 2 -2 0 0 0 0]; internalField uniform 0;"
  echo "boundaryField { inlet { type zeroGradient; } outlet { type fixedValue; value uniform 0; }"
  echo "  walls { type zeroGradient; } cylinder { type zeroGradient; }"
  echo "  front { type empty; } back { type empty; } }"
} > "$case/0/p"
functions() {
  cat <<EOD
functions {
  forces { type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1;
           patches (cylinder); rho rhoInf; rhoInf 1; CofR (0.2 0.2 0); }
  forceCoeffs { type forceCoeffs; libs ("libforces.so"); writeControl timeStep; writeInterval 1;
           patches (cylinder); rho rhoInf; rhoInf 1; CofR (0.2 0.2 0); liftDir (0 1 0);
           dragDir (1 0 0); pitchAxis (0 0 1); magUInf $ubar; lRef 0.1; Aref $(python3 -c "print(0.1 * $tz)"); }
}
EOD
}
schemes() {
  echo "ddtSchemes { default $1; } gradSchemes { default leastSquares; }"
  echo "divSchemes { default none; div(phi,U) $2; div((nuEff*dev2(T(grad(U))))) Gauss linear; }"
  echo "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }"
  echo "snGradSchemes { default corrected; }"
}
start=$(date +%s.%N)
if [[ $kind == 2d1 ]]; then
  { header dictionary controlDict
    echo "application simpleFoam; startFrom startTime; startTime 0; stopAt endTime; endTime 30000;"
    echo "deltaT 1; writeControl timeStep; writeInterval 30000; writeFormat ascii; writePrecision 14;"
    echo "runTimeModifiable false;"
    functions
  } > "$case/system/controlDict"
  { header dictionary fvSchemes; schemes steadyState "bounded $div"; } > "$case/system/fvSchemes"
  { header dictionary fvSolution
    echo "solvers { p { solver GAMG; smoother GaussSeidel; tolerance 1e-12; relTol 0.01; }"
    echo "          U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-14; relTol 0.05; } }"
    echo "SIMPLE { consistent yes; nNonOrthogonalCorrectors 1; residualControl { p 1e-9; U 1e-10; } }"
    echo "relaxationFactors { fields { p 1; } equations { U 0.9; } }"
  } > "$case/system/fvSolution"
  foam "simpleFoam > log.simpleFoam 2>&1"
  last=$(foam "foamListTimes -latestTime" | tail -1)
  foam "postProcess -latestTime -func 'grad(p)' > log.post 2>&1; postProcess -latestTime -func 'grad(U)' >> log.post 2>&1; postProcess -latestTime -func writeCellCentres >> log.post 2>&1"
  secs=$(python3 -c "print('%.1f' % ($(date +%s.%N) - $start))")
  echo "2D-1 m = $m, downstream $down m, $(foam checkMesh -constant 2>&1 | awk '/^ *cells:/ {print $2}') cells, div(phi,U) $div: $last SIMPLE iterations, $secs s"
  grep -q "SIMPLE solution converged" "$case/log.simpleFoam" || echo "  (not converged to the residual control)"
  post steady "$case" "$um" "$last" | sed 's/^/  /'
else
  run_to() {  # end time $1, write every $2 steps, keep the last $3 writes
    { header dictionary controlDict
      echo "application pimpleFoam; startFrom latestTime; startTime 0; stopAt endTime; endTime $1;"
      echo "deltaT 0.002; writeControl timeStep; writeInterval $2; purgeWrite $3; writeFormat ascii; writePrecision 14;"
      echo "runTimeModifiable false; adjustTimeStep no;"
      functions
    } > "$case/system/controlDict"
    foam "pimpleFoam >> log.pimpleFoam 2>&1"
  }
  { header dictionary fvSchemes; schemes backward "$div"; } > "$case/system/fvSchemes"
  { header dictionary fvSolution
    echo "solvers { p { solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0.01; }"
    echo "          pFinal { \$p; relTol 0; }"
    echo "          \"(U|UFinal)\" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; } }"
    echo "PIMPLE { momentumPredictor yes; nOuterCorrectors 2; nCorrectors 2; nNonOrthogonalCorrectors 1; }"
  } > "$case/system/fvSolution"
  run_to 0.2 100 0
  foam "foamDictionary 0.2/U -entry boundaryField.cylinder -set '{ type noSlip; }' > /dev/null"
  run_to "$end" 10 20  # the last 20 writes, 0.4 s, span more than a period
  secs=$(python3 -c "print('%.1f' % ($(date +%s.%N) - $start))")
  echo "2D-2 m = $m, downstream $down m, div(phi,U) $div, to t = $end s: $secs s"
  post shedding "$case" "$um" | sed 's/^/  /'
  # auvloop's wall-stencil evaluation against the forces function object on the written fields.
  foam "postProcess -func 'grad(p)' > log.post 2>&1; postProcess -func 'grad(U)' >> log.post 2>&1; postProcess -func writeCellCentres >> log.post 2>&1"
  times=$(foam "foamListTimes" | grep -E '^[0-9.e+-]+$' | awk '$1 > 1')
  # shellcheck disable=SC2086
  post instants "$case" "$um" $times | sed 's/^/  /'
fi

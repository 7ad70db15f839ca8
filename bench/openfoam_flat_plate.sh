#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Peer comparison: OpenFOAM v1912's simpleFoam with kOmegaSST (Debian package openfoam) on the very
# grid of auvloop's flat-plate-sst case (mesher::flat_plate, written by bench/flat_plate_study
# --polymesh), NASA TMR 2DZP: U = 1 m/s, nu = 2e-7 m^2/s (Re = 5e6 per metre), the TMR's free
# stream k = 2.25e-7 m^2/s^2 and omega = 125 1/s at the inlet; p = 0 at outlet and top; symmetry
# ahead of the plate; on the plate OpenFOAM's wall functions for any y+ (nutUSpaldingWallFunction,
# omegaWallFunction, kqRWallFunction) against auvloop's `--wall wall-function`, their
# counterpart (the first cell's omega fixed to the same blend; auvloop's default any-y+ treatment
# differs from it below y+ of about 25: docs/cfd.md), with E = exp(kappa B) =
# 8.43 so that both use Spalding's law with kappa 0.41 and B 5.2, and SST's gamma1, gamma2 as the
# TMR's (0.553167, 0.440355; OpenFOAM's defaults are 5/9 and 0.44). Schemes as auvloop's: least-
# squares gradients, bounded van Leer for U, k and omega, Gauss linear corrected Laplacians, exact
# wall distance. Both codes run SIMPLE to ITER iterations (default 3000) with U 0.7, p 0.3, k and
# omega 0.7; the script prints each code's Cf(0.97) and CD, their ratio, and the seconds per
# iteration of each (simpleFoam's ExecutionTime, auvloop's wall clock; both on 1 process/thread).
#   bench/openfoam_flat_plate.sh BUILD_DIR LEVEL [FIRST_HEIGHT] [CASE_DIR]
# Grid: level LEVEL of the family; PLATE, UPSTREAM, NORMAL (environment) override the level-0 cell
# counts and FIRST_HEIGHT its first cell (the wall-function grids: docs/cfd.md, "Flat plate").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?build dir}
level=${2:?grid level}
first=${3:-1e-6}
case=${4:-}
iter=${ITER:-3000}
bashrc=/usr/share/openfoam/etc/bashrc
[[ -f $bashrc ]] || { echo "OpenFOAM not found (AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh)"; exit 1; }
if [[ -z $case ]]; then
  case=$(mktemp -d)
  trap 'rm -rf "$case"' EXIT
fi
foam() { bash -c "set +u; source $bashrc >/dev/null 2>&1; cd '$case' && $*"; }
grid=(--level "$level" --first-height "$first" --plate-cells "${PLATE:-256}"
      --upstream-cells "${UPSTREAM:-64}" --normal-cells "${NORMAL:-192}")

rm -rf "$case" && mkdir -p "$case/system" "$case/constant" "$case/0"
"$build/bench/flat_plate_study" "${grid[@]}" --polymesh "$case" > /dev/null
header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }
{ header dictionary transportProperties; echo "transportModel Newtonian; nu 2e-7;"; } \
  > "$case/constant/transportProperties"
{ header dictionary turbulenceProperties
  echo "simulationType RAS; RAS { RASModel kOmegaSST; turbulence on; printCoeffs off;"
  echo "  kOmegaSSTCoeffs { gamma1 0.553167; gamma2 0.440355; } }"
} > "$case/constant/turbulenceProperties"
field() {  # class object dimensions internal inlet plate [outlet/top]
  { header "$1" "$2"
    echo "dimensions $3; internalField uniform $4;"
    echo "boundaryField { inlet { $5 } plate { $6 } outlet { $7 } top { $7 }"
    echo "  symmetry { type symmetry; } front { type empty; } back { type empty; } }"
  } > "$case/0/$2"
}
field volVectorField U "[0 1 -1 0 0 0 0]" "(1 0 0)" "type fixedValue; value uniform (1 0 0);" \
  "type noSlip;" "type zeroGradient;"
field volScalarField p "[0 2 -2 0 0 0 0]" 0 "type zeroGradient;" "type zeroGradient;" \
  "type fixedValue; value uniform 0;"
field volScalarField k "[0 2 -2 0 0 0 0]" 2.25e-7 "type fixedValue; value uniform 2.25e-7;" \
  "type kqRWallFunction; value uniform 2.25e-7;" "type zeroGradient;"
field volScalarField omega "[0 0 -1 0 0 0 0]" 125 "type fixedValue; value uniform 125;" \
  "type omegaWallFunction; value uniform 125;" "type zeroGradient;"
field volScalarField nut "[0 2 -1 0 0 0 0]" 0 "type calculated; value uniform 0;" \
  "type nutUSpaldingWallFunction; kappa 0.41; E 8.43; value uniform 0;" \
  "type calculated; value uniform 0;"
{ header dictionary controlDict
  echo "application simpleFoam; startFrom startTime; startTime 0; stopAt endTime; endTime $iter;"
  echo "deltaT 1; writeControl timeStep; writeInterval $iter; writeFormat ascii; writePrecision 14;"
  echo "runTimeModifiable false;"
  echo "functions { wallShearStress { type wallShearStress; libs (\"libfieldFunctionObjects.so\");"
  echo "  patches (plate); writeControl writeTime; } }"
} > "$case/system/controlDict"
{ header dictionary fvSchemes
  echo "ddtSchemes { default steadyState; } gradSchemes { default leastSquares; }"
  echo "divSchemes { default none; div(phi,U) bounded Gauss vanLeerV; div(phi,k) bounded Gauss vanLeer;"
  echo "  div(phi,omega) bounded Gauss vanLeer; div((nuEff*dev2(T(grad(U))))) Gauss linear; }"
  echo "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }"
  echo "snGradSchemes { default corrected; } wallDist { method exactDistance; }"
} > "$case/system/fvSchemes"
{ header dictionary fvSolution
  echo "solvers { p { solver GAMG; smoother GaussSeidel; tolerance 1e-12; relTol 0.01; }"
  echo "  \"(U|k|omega)\" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-14; relTol 0.1; } }"
  echo "SIMPLE { nNonOrthogonalCorrectors 0; consistent no; }"
  echo "relaxationFactors { fields { p 0.3; } equations { U 0.7; k 0.7; omega 0.7; } }"
} > "$case/system/fvSolution"
foam "simpleFoam > log.simpleFoam 2>&1" || { tail -20 "$case/log.simpleFoam"; exit 1; }
cells=$(foam checkMesh -constant 2>&1 | awk '/^ *cells:/ {print $2}')
of_secs=$(awk '/^ExecutionTime/ {t = $3} END {print t}' "$case/log.simpleFoam")
read -r of_cf of_cd < <(cd "$here" && python3 openfoam_flat_plate.py cf "$case" "$iter")
auv=$("$build/bench/flat_plate_study" "${grid[@]}" --wall wall-function --threads 1 --max-iterations "$iter" --check-every "$iter" \
  | tail -1) || true
auv_cf=$(sed -E 's/.*Cf\(0.97\) ([0-9.e-]+).*/\1/' <<< "$auv")
auv_cd=$(sed -E 's/.* CD ([0-9.e-]+).*/\1/' <<< "$auv")
auv_secs=$(sed -E 's/.* iterations \([^)]*\), ([0-9.]+) s.*/\1/' <<< "$auv")
echo "flat plate level $level, first cell $first m, $cells cells, $iter SIMPLE iterations each (load $(cut -d' ' -f1-3 /proc/loadavg))"
printf '%-10s %10s %10s %14s\n' code "Cf(0.97)" CD "s/iteration"
printf '%-10s %10s %10s %14.5f\n' simpleFoam "$of_cf" "$of_cd" "$(python3 -c "print($of_secs / $iter)")"
printf '%-10s %10s %10s %14.5f\n' auvloop "$auv_cf" "$auv_cd" "$(python3 -c "print($auv_secs / $iter)")"
python3 -c "print('auvloop / simpleFoam: Cf %.4f, CD %.4f, time per iteration %.3f' % ($auv_cf / $of_cf, $auv_cd / $of_cd, ($auv_secs / $iter) / ($of_secs / $iter)))"

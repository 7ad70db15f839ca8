#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Peer comparison: OpenFOAM v1912's simpleFoam with kOmegaSST (Debian package openfoam) on the very
# grid of bench/hull_drag_study (the preset's REMUS 100 hull grid alone, written with --polymesh):
# the hull at U = 1.54 m/s (the stream (-U, 0, 0)), nu = 1e-6 m^2/s, free stream 1 % intensity and
# nu_t / nu = 10 (remus-overset-sst's); "inflow": U, k, omega fixed, p zero gradient; "outflow":
# p = 0, U, k, omega zero gradient; hull: no slip with OpenFOAM's wall functions
# (nutUSpaldingWallFunction with kappa 0.41, E 8.43, omegaWallFunction, kqRWallFunction) against
# auvloop's `--wall wall-function`, their counterpart. Convection SCHEME (environment; default
# upwind): upwind (first order, for U, k, omega: as remus-overset runs), linearUpwind (U second
# order with grad(U) cellLimited leastSquares 1, k and omega upwind: auvloop's
# linear-upwind-limited; unlimited, simpleFoam diverges on this grid within 20 iterations) or
# vanLeer (U bounded vanLeerV, k and omega vanLeer: auvloop's van-leer-skew; both codes diverge
# on the coarse hull grid). Least-squares gradients, Gauss linear corrected Laplacians, exact
# wall distance. SIMPLE with U 0.7, p 0.3, k and omega 0.7, ITER iterations (default 1000: the
# upwind run's drag is steady to 6 digits by 300); the
# drag from OpenFOAM's forces function object (pressure and viscous apart, per unit density),
# auvloop's from hull_drag_study converged to 1e-4 (its own stop), and their ratios.
#   bench/openfoam_hull.sh BUILD_DIR [PRESET] [CASE_DIR]
set -euo pipefail
build=${1:?build dir}
preset=${2:-coarse}
case=${3:-}
iter=${ITER:-1000}
scheme=${SCHEME:-upwind}
bashrc=/usr/share/openfoam/etc/bashrc
[[ -f $bashrc ]] || { echo "OpenFOAM not found (AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh)"; exit 1; }
if [[ -z $case ]]; then
  case=$(mktemp -d)
  trap 'rm -rf "$case"' EXIT
fi
foam() { bash -c "set +u; source $bashrc >/dev/null 2>&1; cd '$case' && $*"; }
case $scheme in
  upwind) div_u="bounded Gauss upwind"; div_t="bounded Gauss upwind"; grad_u=""
          auv_scheme=(--convection upwind --turbulence-convection upwind) ;;
  linearUpwind) div_u="bounded Gauss linearUpwind grad(U)"; div_t="bounded Gauss upwind"
          grad_u="grad(U) cellLimited leastSquares 1;"
          auv_scheme=(--convection linear-upwind-limited --turbulence-convection upwind) ;;
  vanLeer) div_u="bounded Gauss vanLeerV"; div_t="bounded Gauss vanLeer"; grad_u=""
          auv_scheme=(--convection van-leer-skew --turbulence-convection van-leer-skew) ;;
  *) echo "SCHEME: upwind, linearUpwind or vanLeer, got $scheme"; exit 2 ;;
esac
speed=1.54 nu=1e-6
k=$(python3 -c "print(1.5 * (0.01 * $speed) ** 2)")
omega=$(python3 -c "print($k / ($nu * 10))")

rm -rf "$case" && mkdir -p "$case/system" "$case/constant" "$case/0"
"$build/bench/hull_drag_study" --preset "$preset" --polymesh "$case" > /dev/null
header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }
{ header dictionary transportProperties; echo "transportModel Newtonian; nu $nu;"; } \
  > "$case/constant/transportProperties"
{ header dictionary turbulenceProperties
  echo "simulationType RAS; RAS { RASModel kOmegaSST; turbulence on; printCoeffs off; }"
} > "$case/constant/turbulenceProperties"
field() {  # class object dimensions internal inflow outflow hull
  { header "$1" "$2"
    echo "dimensions $3; internalField uniform $4;"
    echo "boundaryField { inflow { $5 } outflow { $6 } hull { $7 } }"
  } > "$case/0/$2"
}
field volVectorField U "[0 1 -1 0 0 0 0]" "(-$speed 0 0)" \
  "type fixedValue; value uniform (-$speed 0 0);" "type zeroGradient;" "type noSlip;"
field volScalarField p "[0 2 -2 0 0 0 0]" 0 "type zeroGradient;" \
  "type fixedValue; value uniform 0;" "type zeroGradient;"
field volScalarField k "[0 2 -2 0 0 0 0]" "$k" "type fixedValue; value uniform $k;" \
  "type zeroGradient;" "type kqRWallFunction; value uniform $k;"
field volScalarField omega "[0 0 -1 0 0 0 0]" "$omega" "type fixedValue; value uniform $omega;" \
  "type zeroGradient;" "type omegaWallFunction; value uniform $omega;"
field volScalarField nut "[0 2 -1 0 0 0 0]" 0 "type calculated; value uniform 0;" \
  "type calculated; value uniform 0;" \
  "type nutUSpaldingWallFunction; kappa 0.41; E 8.43; value uniform 0;"
control() {  # endTime
  { header dictionary controlDict
    echo "application simpleFoam; startFrom latestTime; startTime 0; stopAt endTime; endTime $1;"
    echo "deltaT 1; writeControl timeStep; writeInterval $1; writeFormat ascii; writePrecision 14;"
    echo "runTimeModifiable false;"
    echo "functions { forces { type forces; libs (\"libforces.so\"); patches (hull); rho rhoInf;"
    echo "  rhoInf 1; CofR (0 0 0); writeControl timeStep; writeInterval 1; }"
    echo "  yPlus { type yPlus; libs (\"libfieldFunctionObjects.so\"); writeControl writeTime; } }"
  } > "$case/system/controlDict"
}
schemes() {  # div(phi,U) div(phi,k|omega) [grad(U)]
  { header dictionary fvSchemes
    echo "ddtSchemes { default steadyState; } gradSchemes { default leastSquares; ${3:-} }"
    echo "divSchemes { default none; div(phi,U) $1; div(phi,k) $2;"
    echo "  div(phi,omega) $2; div((nuEff*dev2(T(grad(U))))) Gauss linear; }"
    echo "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }"
    echo "snGradSchemes { default corrected; } wallDist { method exactDistance; }"
  } > "$case/system/fvSchemes"
}
{ header dictionary fvSolution
  echo "solvers { p { solver GAMG; smoother GaussSeidel; tolerance 1e-12; relTol 0.01; }"
  echo "  \"(U|k|omega)\" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-14; relTol 0.1; } }"
  echo "SIMPLE { nNonOrthogonalCorrectors 1; consistent no; }"
  echo "relaxationFactors { fields { p 0.3; } equations { U 0.7; k 0.7; omega 0.7; } }"
} > "$case/system/fvSolution"
# The second-order schemes diverge from the impulsive start (linearUpwind: iteration 18), so
# every run starts with 300 upwind iterations (the upwind flow is steady by then) and goes on
# with its own scheme to ITER; auvloop's converges from the free stream directly.
if [[ $scheme != upwind ]]; then
  control 300
  schemes "bounded Gauss upwind" "bounded Gauss upwind"
  foam "simpleFoam > log.simpleFoam.upwind 2>&1" || { tail -20 "$case/log.simpleFoam.upwind"; exit 1; }
fi
control "$iter"
schemes "$div_u" "$div_t" "$grad_u"
foam "simpleFoam > log.simpleFoam 2>&1" || { tail -20 "$case/log.simpleFoam"; exit 1; }
cells=$(foam checkMesh -constant 2>&1 | awk '/^ *cells:/ {print $2}')
of_secs=$(awk '/^ExecutionTime/ {t = $3} END {print t}' "$case/log.simpleFoam")
# force.dat: time (total) (pressure) (viscous); the drag is the force along the stream (-x). With
# the upwind start the last run's file is under its start time.
read -r of_p of_v < <(python3 - "$case" <<'EOF'
import glob, re, sys
f = sorted(glob.glob(sys.argv[1] + "/postProcessing/forces/*/force.dat"),
           key=lambda p: float(p.split("/")[-2]))[-1]
last = [l for l in open(f) if l.strip() and not l.startswith("#")][-1]
v = [float(x) for x in re.findall(r"[-+0-9.eE]+", last)]
print(-v[4], -v[7])
EOF
)
of_y=$(foam "simpleFoam -postProcess -func yPlus -latestTime 2>&1" | awk '/patch hull/ {print}' | tail -1)
auv=$("$build/bench/hull_drag_study" --preset "$preset" "${auv_scheme[@]}" --wall wall-function \
  --max-iterations "$iter" | tail -2) || true
line=$(head -1 <<< "$auv")
auv_p=$(sed -E 's/.* pressure ([0-9.e+-]+) .*/\1/' <<< "$line")
auv_v=$(sed -E 's/.* shear ([0-9.e+-]+) .*/\1/' <<< "$line")
auv_secs=$(sed -E 's/.*iterations \(([0-9.]+) s\).*/\1/' <<< "$line")
echo "REMUS hull alone ($preset), $cells cells, U $speed m/s, SST, scheme $scheme (load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "simpleFoam: to iteration $iter ($scheme part: $of_secs s); $of_y"
echo "auvloop: $line"
echo "auvloop: $(tail -1 <<< "$auv")"
printf '%-10s %14s %14s %14s %10s\n' code "drag m^4/s^2" pressure shear "N (1025)"
for row in "simpleFoam $of_p $of_v" "auvloop $auv_p $auv_v"; do
  read -r code p v <<< "$row"
  python3 -c "print('%-10s %14.5e %14.5e %14.5e %10.3f' % ('$code', $p + $v, $p, $v, 1025 * ($p + $v)))"
done
python3 -c "print('auvloop / simpleFoam: drag %.4f, pressure %.4f, shear %.4f' % (($auv_p + $auv_v) / ($of_p + $of_v), $auv_p / $of_p, $auv_v / $of_v))"

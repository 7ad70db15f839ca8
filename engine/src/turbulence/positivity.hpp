// SPDX-License-Identifier: GPL-3.0-or-later
// Positivity of a transported turbulence quantity (k, omega), around its solve:
//   1. before the solve, sink_reference: per cell the value ref_c against which a negative net
//      explicit source S_c is taken implicitly, as the rate -S_c / ref_c on the diagonal
//      (Patankar): ref_c = max(phi_c, floor), except at a local minimum (phi_c at most every
//      in-flow face neighbour's value), where ref_c = max(phi_c, mean_c, floor) with mean_c the
//      neighbours' mean weighted by the orthogonal Laplacian's coefficients |S_f|^2 / (S_f . d_f)
//      (exact for a linear field on an orthogonal grid, however graded). Where the cell is not a
//      minimum the converged solution is the equation's; at a minimum the sink is scaled by
//      phi_c / ref_c, so a scheme cannot deepen it without bound (what a TVD scheme does at an
//      extremum, reverting to upwind, done for the row). With ref_c = phi_c everywhere, a sink
//      that does not vanish with phi_c (a deferred correction carrying a neighbour's value out of
//      the cell) is a trap: the rate grows as phi_c falls, and on the REMUS hull cells sat at 1e-13
//      1/s beside neighbours at 1,000 until the cross-diffusion's sign changed over the tiny omega
//      and threw one to 1e17 (docs/cfd.md, "Positivity"). The solve's row scaling uses ref_c too.
//   2. after the solve, bound (OpenFOAM's bound()): every cell with phi_c below floor (or not a
//      number) gets the area-weighted mean over its internal faces of its in-flow neighbours'
//      max(phi_n, floor) (the floor if it has none), computed from the solve's values and
//      written once all are computed. Raised to the floor instead, the cell's next solve would
//      evaluate its implicit sinks (above; the SST cross-diffusion's rate ~ 1 / omega^2) at the
//      floor value and hold it there whatever its neighbours hold.
// Both are per-cell gathers over the cell's faces in ascending order: the same bits for any
// number of threads. overset may be nullptr (a single grid); its holes are not in the flow.
#pragma once

#include <vector>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/overset.hpp"

namespace auvloop::engine::turbulence {

// Step 1: ref (resized to the cells) from phi.
void sink_reference(const fv::Mesh& mesh, const fv::Overset* overset,
                    const std::vector<double>& phi, double floor, std::vector<double>& ref);

// Step 2: returns how many cells were raised; scratch is resized to the cells.
long bound(const fv::Mesh& mesh, const fv::Overset* overset, std::vector<double>& phi, double floor,
           std::vector<double>& scratch);

}  // namespace auvloop::engine::turbulence

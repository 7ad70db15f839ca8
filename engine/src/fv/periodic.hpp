// SPDX-License-Identifier: GPL-3.0-or-later
// Translational periodic patches as coupled faces (private to engine/src/fv).
//
// Each face of a periodic patch is matched to the face of its neighbour patch that it covers
// after a translation by the separation vector s (the difference of the two patches' mean face
// centres). The matched pair becomes one internal face between the two owner cells: the area and
// centre are those of the owner's side, and the neighbour cell is seen through it at its centre
// shifted by +-s. With internal faces whose neighbour centre is x_N + shift, every operator works
// unchanged (OpenFOAM's cyclic patches reach the same through patch-neighbour fields; merging the
// pair into the face list keeps one code path and makes the matrix pattern include the coupling,
// which the direct and DIC solvers need).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::engine::fv {

struct CoupledGrid {
  mesher::Grid grid;  // periodic pairs merged into the internal faces; periodic patches empty
  mesher::GridGeometry geometry;
  std::vector<Eigen::Vector3d> shift;  // per internal face: x_N seen from the owner = x_N + shift
};

// nullopt when the grid has no periodic patch. Throws std::invalid_argument naming the patch and
// face when the patches do not pair up, a face has no translated partner, or a periodic
// direction has fewer than three cells (the coupled face would duplicate an internal one).
std::optional<CoupledGrid> couple_periodic(const mesher::Grid& grid,
                                           const mesher::GridGeometry& geometry);

}  // namespace auvloop::engine::fv

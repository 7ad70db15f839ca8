// SPDX-License-Identifier: GPL-3.0-or-later
// Builds a face-addressed Grid from a list of hexahedra given by their corner points, so that the
// structured generators (hull, fins) only have to say which points make up which cell.
//
// A hexahedron lists its corners in VTK order (bottom 0-1-2-3, top 4-5-6-7 above 0-1-2-3; positive
// volume when 0-1, 0-3, 0-4 form a right-handed triad). Corners may repeat: a face whose repeated
// corners leave three distinct points becomes a triangle, and a face with fewer disappears. That is
// how a revolved grid gets prisms along the axis (a collapsed edge) and a fin grid its triangular
// columns at the leading and trailing edges, without zero-area faces.
//
// Faces shared by two cells become internal faces (owner = the lower cell index, upper-triangular
// order); the others are boundary faces, which a classifier assigns to patches.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

using HexCorners = std::array<int, 8>;

class CellAssembler {
 public:
  int add_point(const Eigen::Vector3d& p);
  void add_hex(const HexCorners& corners);
  [[nodiscard]] const std::vector<Eigen::Vector3d>& points() const { return points_; }
  [[nodiscard]] int cells() const { return static_cast<int>(cells_.size()); }

  // Signed volume of a (possibly collapsed) hexahedron from its faces (divergence theorem):
  // generators use it on one representative cell to choose the corner order of a whole block.
  [[nodiscard]] double signed_volume(const HexCorners& corners) const;

  // `classify` receives the points of a boundary face and returns an index into `patches`; a
  // negative index is an error (the face belongs nowhere). Throws std::runtime_error when two
  // cells disagree about the orientation of their shared face.
  [[nodiscard]] Grid build(const std::string& name,
                           const std::vector<std::pair<std::string, PatchType>>& patches,
                           const std::function<int(std::span<const int>)>& classify) const;

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<HexCorners> cells_;
};

// The faces of a hexahedron with outward (right-hand) point order, collapsed corners removed; faces
// with fewer than three distinct points are left out.
std::vector<std::vector<int>> hex_faces(const HexCorners& c);

}  // namespace auvloop::mesher

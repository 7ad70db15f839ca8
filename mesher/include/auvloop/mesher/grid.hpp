// SPDX-License-Identifier: GPL-3.0-or-later
// The polyhedral grid shared by the mesher and the CFD engine (docs/grid.md).
//
// Face-addressed, as OpenFOAM's polyMesh: every face is an ordered list of point indices whose
// right-hand normal points out of its owner cell. Internal faces come first, each with
// owner < neighbour; boundary faces follow, grouped contiguously by patch. Cells exist only as the
// faces that bound them. Invariants (checked by validate()):
//   - every cell is closed: the sum of its outward face area vectors vanishes to round-off;
//   - every cell has positive volume;
//   - internal faces have owner < neighbour; patches tile the boundary faces in order.
// A grid has a rigid placement (`placement`) so that component grids of an overset system can move
// with the vehicle and fins can turn about their posts without touching the points.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace auvloop::mesher {

enum class PatchType {
  wall,      // no-slip (moving with the grid)
  inlet,     // velocity inlet
  outlet,    // pressure outlet
  symmetry,  // slip / symmetry plane
  empty,     // the out-of-plane faces of a one-cell-thick 2D grid
  periodic,  // paired with another patch (neighbour_patch)
  overset,   // the outer boundary of a component grid: values come from donors
};

const char* to_string(PatchType t);

struct Patch {
  std::string name;
  PatchType type = PatchType::wall;
  int start = 0;  // first face index (global)
  int size = 0;
  int neighbour_patch = -1;  // periodic only
};

struct Zone {
  std::string name;
  std::vector<int> cells;
};

struct Grid {
  std::string name;
  std::vector<Eigen::Vector3d> points;
  std::vector<int> face_offsets{0};  // face f has points face_points[face_offsets[f] .. [f + 1])
  std::vector<int> face_points;
  std::vector<int> owner;      // one per face
  std::vector<int> neighbour;  // one per internal face
  std::vector<Patch> patches;
  std::vector<Zone> zones;
  int cells = 0;
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();  // grid frame -> body frame

  [[nodiscard]] int faces() const { return static_cast<int>(owner.size()); }
  [[nodiscard]] int internal_faces() const { return static_cast<int>(neighbour.size()); }
  [[nodiscard]] int face_size(int f) const {
    return face_offsets[static_cast<std::size_t>(f) + 1] -
           face_offsets[static_cast<std::size_t>(f)];
  }
  [[nodiscard]] int face_point(int f, int k) const {
    return face_points[static_cast<std::size_t>(face_offsets[static_cast<std::size_t>(f)] + k)];
  }
  void add_face(std::initializer_list<int> points, int owner_cell);
  void add_face(const std::vector<int>& points, int owner_cell);
};

// Geometry derived from the points, in the grid's own frame (OpenFOAM's decomposition: faces into
// triangles about their point average, cells into pyramids about their face-centre average).
struct GridGeometry {
  std::vector<Eigen::Vector3d> face_centre;
  std::vector<Eigen::Vector3d>
      face_area;  // area vector, |S| = area, along the owner's outward normal
  std::vector<Eigen::Vector3d> cell_centre;
  std::vector<double> cell_volume;
};

GridGeometry compute_geometry(const Grid& g);

struct GridQuality {
  int cells = 0, faces = 0, internal_faces = 0, points = 0;
  double total_volume = 0;
  double min_volume = 0;
  double max_closure_error = 0;        // max over cells of |sum S| / sum |S|
  double max_non_orthogonality = 0;    // deg: angle between S and the owner-neighbour vector
  double max_skewness = 0;             // distance from the face centre to the centre line / |d|
  double max_aspect_ratio = 0;         // of a cell: max face area / min face area
  int worst_cell = -1;                 // the cell with the smallest volume
  int worst_non_orthogonal_face = -1;  // where max_non_orthogonality occurs
  int worst_skewed_face = -1;          // where max_skewness occurs
};

GridQuality measure_quality(const Grid& g, const GridGeometry& geo);

// The mesh report: one grid's counts and quality as JSON-ready text rows.
std::string quality_table(const Grid& g, const GridQuality& q);

// Throws std::runtime_error naming the first violated invariant (face, cell and reason).
void validate(const Grid& g, const GridGeometry& geo, double closure_tolerance = 1e-9);

}  // namespace auvloop::mesher

// SPDX-License-Identifier: GPL-3.0-or-later
// A general overset system whose grids move against each other (a foil pitching in its own grid
// over a background, a test's turning box), as one composite mesh with its coupling: the grids,
// the assembler, the composite mesh (each grid merged at its placement at construction, P0),
// and the Overset. A step of a driver:
//   1. place(k, axes) for every grid that moved: grid k's axes in the system's relative to where
//      it was merged (its placement becomes axes * P0_k);
//   2. reassemble(): the assembly at the present placements, in the composite's numbers, passed
//      to the Overset with every component's orientation (Overset::update, set_orientation);
//   3. the motion of each grid's axes (fv::placed_motion with axes(k)) to Pimple::set_motion,
//      then Pimple::step, which carries the fields onto the new statuses.
// A vehicle's system (hull, fins turning on their posts, background) uses the mesher's
// incremental update instead; the coupling is the same.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/overset.hpp"
#include "auvloop/geometry/surface_fwd.hpp"
#include "auvloop/mesher/composite_grid.hpp"

namespace auvloop::engine::fv {

class MovingOverset {
 public:
  struct Component {
    mesher::Grid grid;                                   // at its placement P0
    int priority = 0;                                    // mesher::OversetComponent
    std::shared_ptr<const geometry::SurfaceMesh> solid;  // in the grid's frame; null: none
  };
  // Assembles the grids at their placements. Throws std::invalid_argument as OversetAssembler
  // and Overset do (an orphan named with its cell).
  explicit MovingOverset(std::vector<Component> components, mesher::OversetSettings settings = {});
  MovingOverset(const MovingOverset&) = delete;
  MovingOverset& operator=(const MovingOverset&) = delete;
  ~MovingOverset();

  [[nodiscard]] const Mesh& mesh() const { return *mesh_; }
  [[nodiscard]] const Overset& overset() const { return *overset_; }
  [[nodiscard]] Overset& overset() { return *overset_; }
  [[nodiscard]] const mesher::CompositeGrid& composite() const { return composite_; }
  [[nodiscard]] const mesher::Grid& grid(int k) const {
    return *grids_[static_cast<std::size_t>(k)];
  }
  [[nodiscard]] int components() const { return static_cast<int>(grids_.size()); }
  // Step 1. Throws std::invalid_argument for a component out of range.
  void place(int k, const Eigen::Isometry3d& axes);
  [[nodiscard]] const Eigen::Isometry3d& axes(int k) const {
    return axes_[static_cast<std::size_t>(k)];
  }
  // Step 2; the assembly's statistics (counts, wall time). Throws std::invalid_argument when the
  // new assembly leaves an orphan, keeping the previous coupling.
  const mesher::Assembly& reassemble();
  [[nodiscard]] const mesher::Assembly& assembly() const { return assembly_; }

 private:
  std::vector<std::unique_ptr<mesher::Grid>> grids_;  // stable addresses: the assembler's
  std::vector<Eigen::Isometry3d> placement0_, axes_;
  std::unique_ptr<mesher::OversetAssembler> assembler_;
  mesher::CompositeGrid composite_;
  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<Overset> overset_;
  mesher::Assembly assembly_;
};

}  // namespace auvloop::engine::fv

// SPDX-License-Identifier: GPL-3.0-or-later
// A vehicle's overset system in the flow: the hull grid, one grid per fin turning on its post,
// the background (mesher::GridSystem order), merged into one composite mesh at the fin
// deflections it is built with (d0), with its coupling. A step of a driver:
//   1. set_fins(d): the mesher's incremental update (OversetAssembler::update: only the cells
//      near the fins re-examined) at the new time level's deflections, passed to the Overset in
//      the composite's numbers with every component's orientation (Overset::update,
//      set_orientation): fin k's axes turned about its post by d_k - d0_k, the hull's and the
//      background's the body's;
//   2. motions(body, rates) to Pimple::set_motion: every grid with the body's motion, fin k's
//      axes turning besides at rates_k (rad/s) about its post (fv::placed_motion);
//   3. Pimple::step, which carries the fields onto the new statuses.
// Invariant: after every successful set_fins the Overset's stencils are those of a full assembly
// at the present deflections (the mesher's update is tested equal to it), every fringe cell with
// active donors only (Overset checks it; an orphan throws and keeps the previous coupling).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "auvloop/engine/fv/mesh.hpp"
#include "auvloop/engine/fv/motion.hpp"
#include "auvloop/engine/fv/overset.hpp"
#include "auvloop/engine/state_archive.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "auvloop/mesher/composite_grid.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "auvloop/mesher/overset.hpp"

namespace auvloop::engine::fv {

class VehicleOverset {
 public:
  // Assembles the system at system.fin_deflections. Throws std::invalid_argument as the
  // assembler and Overset do (an orphan named with its cell).
  VehicleOverset(mesher::GridSystem system, const geometry::Vehicle& vehicle,
                 mesher::OversetSettings settings = {});
  VehicleOverset(const VehicleOverset&) = delete;
  VehicleOverset& operator=(const VehicleOverset&) = delete;
  ~VehicleOverset();

  [[nodiscard]] const Mesh& mesh() const { return *mesh_; }
  [[nodiscard]] const Overset& overset() const { return *overset_; }
  [[nodiscard]] Overset& overset() { return *overset_; }
  [[nodiscard]] const mesher::CompositeGrid& composite() const { return composite_; }
  [[nodiscard]] const mesher::GridSystem& system() const { return *system_; }
  [[nodiscard]] int fins() const { return static_cast<int>(system_->fins.size()); }
  // Component numbers in the composite: hull 0, fin k is 1 + k, the background 1 + fins().
  [[nodiscard]] static int fin_component(int k) { return 1 + k; }
  [[nodiscard]] int background_component() const { return 1 + fins(); }
  // The composite patch name of fin k's wall ("<fin>/<fin>") and of the hull's ("hull/hull").
  [[nodiscard]] std::string fin_wall(int k) const;
  [[nodiscard]] static std::string hull_wall() { return "hull/hull"; }

  // Step 1 (rad, one per fin). Throws std::invalid_argument for a wrong count or an orphan,
  // keeping the previous deflections and coupling.
  const mesher::Assembly& set_fins(const std::vector<double>& deflections);
  // Exact checkpoint: the deflections and the assembly. An incremental update keeps a fringe
  // cell's donor while it still contains the centre, so the stencils depend on the path of
  // deflections, not on the present ones alone; load() moves the fins to the stored deflections
  // and then takes the stored assembly, so that the next set_fins() is as it would have been.
  // Throws std::runtime_error on a record of another system, keeping the present state.
  void save(StateWriter& out) const;
  void load(StateReader& in);
  [[nodiscard]] const std::vector<double>& deflections() const { return system_->fin_deflections; }
  [[nodiscard]] const mesher::Assembly& assembly() const { return assembly_; }
  // Fin k's axes in the body frame relative to where it was merged.
  [[nodiscard]] Eigen::Isometry3d fin_axes(int k) const;
  // Every component's axes relative to where it was merged (fin k's fin_axes(k), the others
  // the identity), and per component a flag per cell: in the flow (not a hole). What
  // turbulence::WallDistances::update needs after set_fins.
  [[nodiscard]] std::vector<Eigen::Isometry3d> component_axes() const;
  [[nodiscard]] std::vector<std::vector<char>> cells_in_flow() const;
  // Output (flow_snapshot.cpp): the composite grid with every fin grid turned to its present
  // deflection, points in the body frame (the mesh the solver holds keeps them where they were
  // merged); and the composite cell holding the body-frame point x in the flow: of the grids
  // whose cell there is not a hole, the first with an active cell, in the order fins, hull,
  // background, else the first with a fringe cell; -1 in a solid or outside every grid.
  [[nodiscard]] mesher::Grid placed_grid() const;
  [[nodiscard]] int locate(const Eigen::Vector3d& x) const;
  // Step 2: rates (rad/s, one per fin; empty: fins at rest).
  [[nodiscard]] std::vector<FrameMotion> motions(const FrameMotion& body,
                                                 const std::vector<double>& rates) const;

 private:
  std::unique_ptr<mesher::GridSystem> system_;  // stable address: the assembler's
  std::vector<double> merged_at_;               // d0
  std::unique_ptr<mesher::OversetAssembler> assembler_;
  mesher::CompositeGrid composite_;
  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<Overset> overset_;
  mesher::Assembly assembly_;
  void orient();
  // load(): what makes a stored grid assembly unusable here (empty: nothing).
  [[nodiscard]] std::string misfit(const mesher::GridAssembly& g, std::size_t k) const;
};

}  // namespace auvloop::engine::fv

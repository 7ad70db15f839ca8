// SPDX-License-Identifier: GPL-3.0-or-later
// A general overset system whose grids move against each other (moving_overset.hpp states the
// steps of a driver).
#include "auvloop/engine/fv/moving_overset.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace auvloop::engine::fv {

MovingOverset::MovingOverset(std::vector<Component> components, mesher::OversetSettings settings) {
  for (auto& c : components) {
    placement0_.push_back(c.grid.placement);
    axes_.push_back(Eigen::Isometry3d::Identity());
    grids_.push_back(std::make_unique<mesher::Grid>(std::move(c.grid)));
  }
  std::vector<mesher::OversetComponent> list;
  std::vector<const mesher::Grid*> grids;
  for (std::size_t k = 0; k < components.size(); ++k) {
    // The assembler copies the solids.
    list.push_back({grids_[k].get(), components[k].priority, components[k].solid.get()});
    grids.push_back(grids_[k].get());
  }
  assembler_ = std::make_unique<mesher::OversetAssembler>(list, settings);
  assembly_ = assembler_->assemble();
  composite_ = mesher::composite_grid(grids);
  mesh_ = std::make_unique<Mesh>(composite_.grid);
  overset_ = std::make_unique<Overset>(*mesh_, mesher::composite_stencils(composite_, assembly_),
                                       composite_.cell_offset);
}

MovingOverset::~MovingOverset() = default;

void MovingOverset::place(int k, const Eigen::Isometry3d& axes) {
  if (k < 0 || k >= components())
    throw std::invalid_argument(
        fmt::format("MovingOverset::place: component {} of {}", k, components()));
  const auto ks = static_cast<std::size_t>(k);
  axes_[ks] = axes;
  grids_[ks]->placement = axes * placement0_[ks];
}

const mesher::Assembly& MovingOverset::reassemble() {
  auto next = assembler_->assemble();
  overset_->update(mesher::composite_stencils(composite_, next));
  std::vector<Eigen::Matrix3d> orientation;
  for (const auto& a : axes_) orientation.push_back(a.linear());
  overset_->set_orientation(std::move(orientation));
  assembly_ = std::move(next);
  return assembly_;
}

}  // namespace auvloop::engine::fv

// SPDX-License-Identifier: GPL-3.0-or-later
// A vehicle's overset system in the flow (vehicle_overset.hpp states the steps of a driver).
#include "auvloop/engine/fv/vehicle_overset.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/mesher/fin_grid.hpp"

namespace auvloop::engine::fv {

VehicleOverset::VehicleOverset(mesher::GridSystem system, const geometry::Vehicle& vehicle,
                               mesher::OversetSettings settings)
    : system_(std::make_unique<mesher::GridSystem>(std::move(system))) {
  merged_at_ = system_->fin_deflections;
  assembler_ = std::make_unique<mesher::OversetAssembler>(*system_, vehicle, settings);
  assembly_ = assembler_->assemble(merged_at_);
  composite_ = mesher::composite_grid(system_->grids());
  mesh_ = std::make_unique<Mesh>(composite_.grid);
  overset_ = std::make_unique<Overset>(*mesh_, mesher::composite_stencils(composite_, assembly_),
                                       composite_.cell_offset);
}

VehicleOverset::~VehicleOverset() = default;

std::string VehicleOverset::fin_wall(int k) const {
  const auto& name = system_->fins.at(static_cast<std::size_t>(k)).name;
  return name + "/" + name;
}

Eigen::Isometry3d VehicleOverset::fin_axes(int k) const {
  const auto ks = static_cast<std::size_t>(k);
  const auto& fin = system_->fin_geometry.at(ks);
  return mesher::fin_placement(fin, system_->fin_deflections[ks]) *
         mesher::fin_placement(fin, merged_at_[ks]).inverse();
}

const mesher::Assembly& VehicleOverset::set_fins(const std::vector<double>& deflections) {
  if (deflections.size() != system_->fins.size())
    throw std::invalid_argument(fmt::format("VehicleOverset::set_fins: {} deflections for {} fins",
                                            deflections.size(), system_->fins.size()));
  const auto before = system_->fin_deflections;
  try {
    auto next = assembler_->update(assembly_, deflections);
    overset_->update(mesher::composite_stencils(composite_, next));
    assembly_ = std::move(next);
  } catch (...) {
    // The grids and the assembler's state back where the coupling is (a full assembly: the
    // failed update left the assembler at the new deflections).
    assembly_ = assembler_->assemble(before);
    throw;
  }
  orient();
  return assembly_;
}

void VehicleOverset::save(StateWriter& out) const {
  out.tag("overset assembly");
  out.put(system_->fin_deflections);
  out.put(static_cast<std::int64_t>(assembly_.grids.size()));
  for (const auto& g : assembly_.grids) {
    out.put(g.status);
    out.put(g.donor_grid);
    out.put(g.donor_cell);
    out.put(g.fallback);
    out.put(g.chained);
    out.put(g.stencil_offsets);
    out.put(g.stencil_grids);
    out.put(g.stencil_cells);
    out.put(g.stencil_weights);
  }
}

void VehicleOverset::load(StateReader& in) {
  in.expect_tag("overset assembly");
  mesher::Assembly stored;
  stored.fin_deflections = in.get_vector();
  if (stored.fin_deflections.size() != system_->fins.size())
    in.fail(fmt::format("{} fins stored, this system has {}", stored.fin_deflections.size(),
                        system_->fins.size()));
  const auto grids = in.get<std::int64_t>();
  if (grids != static_cast<std::int64_t>(assembly_.grids.size()))
    in.fail(fmt::format("{} grids stored, this system has {}", grids, assembly_.grids.size()));
  for (std::size_t k = 0; k < assembly_.grids.size(); ++k) {
    mesher::GridAssembly g;
    g.status = in.get_vector<mesher::CellStatus>();
    g.donor_grid = in.get_vector<int>();
    g.donor_cell = in.get_vector<int>();
    g.fallback = in.get_vector<char>();
    g.chained = in.get_vector<char>();
    g.stencil_offsets = in.get_vector<int>();
    g.stencil_grids = in.get_vector<int>();
    g.stencil_cells = in.get_vector<int>();
    g.stencil_weights = in.get_vector<double>();
    if (g.status.size() != assembly_.grids[k].status.size())
      in.fail(fmt::format("grid {}: {} cells stored, this system has {}", k, g.status.size(),
                          assembly_.grids[k].status.size()));
    stored.grids.push_back(std::move(g));
  }
  try {
    if (stored.fin_deflections != system_->fin_deflections) (void)set_fins(stored.fin_deflections);
    overset_->update(mesher::composite_stencils(composite_, stored));
  } catch (const std::invalid_argument& e) {
    in.fail(fmt::format("the stored assembly does not fit: {}", e.what()));
  }
  assembly_ = std::move(stored);
  orient();
}

void VehicleOverset::orient() {
  std::vector<Eigen::Matrix3d> orientation(system_->grids().size(), Eigen::Matrix3d::Identity());
  for (int k = 0; k < fins(); ++k)
    orientation[static_cast<std::size_t>(fin_component(k))] = fin_axes(k).linear();
  overset_->set_orientation(std::move(orientation));
}

std::vector<Eigen::Isometry3d> VehicleOverset::component_axes() const {
  std::vector<Eigen::Isometry3d> axes(static_cast<std::size_t>(overset_->components()),
                                      Eigen::Isometry3d::Identity());
  for (int k = 0; k < fins(); ++k) axes[static_cast<std::size_t>(fin_component(k))] = fin_axes(k);
  return axes;
}

std::vector<std::vector<char>> VehicleOverset::cells_in_flow() const {
  const auto& offset = composite_.cell_offset;
  std::vector<std::vector<char>> in_flow(offset.size());
  for (std::size_t g = 0; g < offset.size(); ++g)
    for (int c = 0; c < composite_.cells_of(g); ++c)
      in_flow[g].push_back(overset_->status(offset[g] + c) != mesher::CellStatus::hole);
  return in_flow;
}

std::vector<FrameMotion> VehicleOverset::motions(const FrameMotion& body,
                                                 const std::vector<double>& rates) const {
  if (!rates.empty() && rates.size() != system_->fins.size())
    throw std::invalid_argument(fmt::format("VehicleOverset::motions: {} rates for {} fins",
                                            rates.size(), system_->fins.size()));
  std::vector<FrameMotion> out(system_->grids().size(), body);
  for (int k = 0; k < fins(); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const auto& fin = system_->fin_geometry[ks];
    const double rate = rates.empty() ? 0.0 : rates[ks];
    out[static_cast<std::size_t>(fin_component(k))] =
        placed_motion(body, fin_axes(k), rate * fin.span_axis(), fin.post_origin());
  }
  return out;
}

}  // namespace auvloop::engine::fv

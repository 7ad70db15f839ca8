// SPDX-License-Identifier: GPL-3.0-or-later
// A vehicle's overset system in the flow (vehicle_overset.hpp states the steps of a driver).
#include "auvloop/engine/fv/vehicle_overset.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

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

namespace {
// The arrays of a grid's assembly, in the checkpoint's order (one list for writing and reading).
template <class G, class F>
void each_array(G& g, F&& f) {
  f(g.status);
  f(g.donor_grid);
  f(g.donor_cell);
  f(g.fallback);
  f(g.chained);
  f(g.stencil_offsets);
  f(g.stencil_grids);
  f(g.stencil_cells);
  f(g.stencil_weights);
}
}  // namespace

// What makes a stored grid assembly unusable on this system (empty: nothing): per-cell arrays of
// another length, stencil offsets that do not run from 0 up to the entries, donors outside the
// grids. A record that passes may still be another run's; the key in the loop's checkpoint
// guards that.
std::string VehicleOverset::misfit(const mesher::GridAssembly& g, std::size_t k) const {
  const auto grids = system_->grids();
  const std::size_t cells = assembly_.grids[k].status.size();
  if (g.status.size() != cells)
    return fmt::format("{} cells stored, this system has {}", g.status.size(), cells);
  if (g.donor_grid.size() != cells || g.donor_cell.size() != cells || g.fallback.size() != cells ||
      g.chained.size() != cells || g.stencil_offsets.size() != cells + 1)
    return "per-cell arrays of different lengths";
  const auto entries = g.stencil_cells.size();
  if (g.stencil_grids.size() != entries || g.stencil_weights.size() != entries ||
      g.stencil_offsets.front() != 0 ||
      static_cast<std::size_t>(g.stencil_offsets.back()) != entries ||
      !std::is_sorted(g.stencil_offsets.begin(), g.stencil_offsets.end()))
    return "stencil offsets that do not index the stencils";
  const auto in_grid = [&](int grid, int cell) {
    return grid >= 0 && static_cast<std::size_t>(grid) < grids.size() && cell >= 0 &&
           cell < grids[static_cast<std::size_t>(grid)]->cells;
  };
  for (std::size_t e = 0; e < entries; ++e)
    if (!in_grid(g.stencil_grids[e], g.stencil_cells[e]))
      return fmt::format("stencil entry {}: donor cell {} of grid {} does not exist", e,
                         g.stencil_cells[e], g.stencil_grids[e]);
  for (std::size_t c = 0; c < cells; ++c)
    if (g.donor_grid[c] != -1 && !in_grid(g.donor_grid[c], g.donor_cell[c]))
      return fmt::format("cell {}: donor cell {} of grid {} does not exist", c, g.donor_cell[c],
                         g.donor_grid[c]);
  return {};
}

void VehicleOverset::save(StateWriter& out) const {
  out.tag("overset assembly");
  out.put(system_->fin_deflections);
  out.put(static_cast<std::int64_t>(assembly_.grids.size()));
  for (const auto& g : assembly_.grids) each_array(g, [&](const auto& v) { out.put(v); });
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
    each_array(
        g, [&](auto& v) { v = in.get_vector<typename std::decay_t<decltype(v)>::value_type>(); });
    if (const auto wrong = misfit(g, k); !wrong.empty())
      in.fail(fmt::format("grid {}: {}", k, wrong));
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

mesher::Grid VehicleOverset::placed_grid() const {
  mesher::Grid g = composite_.grid;
  // The components' points lie one after another in the composite, in grids() order.
  std::size_t first = system_->hull.points.size();
  for (int k = 0; k < fins(); ++k) {
    const auto& fin = system_->fins[static_cast<std::size_t>(k)];
    const Eigen::Isometry3d axes = fin_axes(k);
    for (std::size_t i = 0; i < fin.points.size(); ++i)
      g.points[first + i] = axes * g.points[first + i];
    first += fin.points.size();
  }
  return g;
}

int VehicleOverset::locate(const Eigen::Vector3d& x) const {
  const int grids = 2 + fins();
  int fringe = -1;
  for (int n = 0; n < grids; ++n) {
    // fins first (components 1 .. fins()), then the hull (0), then the background
    const int g = n < fins() ? fin_component(n) : (n == fins() ? 0 : background_component());
    const int cell = assembler_->locate(g, x);
    if (cell < 0) continue;
    const int c = composite_.cell_offset[static_cast<std::size_t>(g)] + cell;
    if (overset_->active(c)) return c;
    if (fringe < 0 && overset_->in_flow(c)) fringe = c;
  }
  return fringe;
}

}  // namespace auvloop::engine::fv

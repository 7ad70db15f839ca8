// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's flow for a person to look at (issue 18 item 6; engine/cfd_plant.hpp):
//   1. the stern plane: the hull's tail is the aftmost centre of its wall faces; on the lattice
//      around it in z = 0, no value inside the hull's profile (the background's cells that
//      straddle the wall would give one), else each point's cell (VehicleOverset::locate: an active
//      cell of the highest-priority grid, fins before hull before background, else a fringe cell;
//      none in a solid) gives |U - w_k(x_c)|, U the water's velocity in the axes of the cell's grid
//      k and w_k that grid's velocity at the cell centre (its FrameMotion): the speed relative to
//      the vehicle, or to a fin near a turning fin;
//   2. the upper fin: the fin whose wall faces' mean centre lies highest (least z); per wall face
//      its centre with the fin at zero deflection (the grids were merged there), its side from
//      the outward normal n = -S / |S| (the fluid's area vector S points into the fin): the
//      sign of n_y, or 0 (the tip and the root, |n_y| < 0.2),
//      and rho p of its cell (zero-gradient pressure at a wall);
//   3. the fields for ParaView: the composite grid with the fin grids turned to their
//      deflections (VehicleOverset::placed_grid), the vectors of a fin's cells turned from its
//      grid's axes into the body's by the same rotation.
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "auvloop/engine/fv/field.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/grid_io.hpp"
#include "cfd_plant_impl.hpp"

namespace auvloop::engine {

namespace {
const mesher::Patch& wall(const fv::Mesh& mesh, const std::string& name) {
  return mesh.grid().patches[static_cast<std::size_t>(fv::patch_index(mesh, name))];
}
}  // namespace

FlowSnapshot CfdPlant::snapshot(double time, double h, double aft, double ahead,
                                double half_width) const {
  if (!(h > 0 && aft >= 0 && ahead >= 0 && half_width > 0 && aft + ahead > 0))
    throw std::invalid_argument(fmt::format(
        "CfdPlant::snapshot: spacing {} m, window {} m aft, {} m ahead, {} m either side", h, aft,
        ahead, half_width));
  const auto& m = *impl_;
  const auto& mesh = m.sys->mesh();
  const auto& overset = m.sys->overset();
  const auto& flow = *m.flow;
  FlowSnapshot s;
  s.time = time;
  // 1.
  const auto& hull = wall(mesh, fv::VehicleOverset::hull_wall());
  double tail = std::numeric_limits<double>::infinity();
  for (int i = 0; i < hull.size; ++i) tail = std::min(tail, mesh.face_centre(hull.start + i).x());
  s.h = h;
  s.x0 = tail - aft;
  s.y0 = -half_width;
  s.nx = 1 + static_cast<int>(std::floor((aft + ahead) / h + 1e-9));
  s.ny = 1 + static_cast<int>(std::floor(2 * half_width / h + 1e-9));
  s.speed.assign(static_cast<std::size_t>(s.nx) * static_cast<std::size_t>(s.ny),
                 std::numeric_limits<double>::quiet_NaN());
  const geometry::MyringProfile profile(m.vehicle.hull);
  const double cb = m.vehicle.mass.cb_station;
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      const double x = s.x0 + i * h, y = s.y0 + j * h, station = cb - x;
      if (station >= 0 && station <= profile.length() && std::abs(y) < profile.radius(station))
        continue;  // in the hull (the background's cells there straddle its wall)
      const int c = m.sys->locate({x, y, 0.0});
      if (c < 0) continue;
      const auto& grid_motion = flow.motion()[static_cast<std::size_t>(overset.component_of(c))];
      s.speed[static_cast<std::size_t>(j) * static_cast<std::size_t>(s.nx) +
              static_cast<std::size_t>(i)] =
          (flow.U.cell(c) - grid_motion.at(mesh.centre(c))).norm();
    }
  }
  // 2.
  int upper = -1;
  const mesher::Patch* upper_wall = nullptr;
  double highest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m.sys->fins(); ++k) {
    const auto& patch = wall(mesh, m.sys->fin_wall(k));
    double z = 0;
    for (int i = 0; i < patch.size; ++i) z += mesh.face_centre(patch.start + i).z();
    if (patch.size > 0 && z / patch.size < highest) {
      highest = z / patch.size;
      upper = k;
      upper_wall = &patch;
    }
  }
  if (upper_wall != nullptr) {
    const auto& patch = *upper_wall;
    s.fin = m.vehicle.fin_set.fins.at(static_cast<std::size_t>(upper)).name;
    s.deflection = m.sys->deflections()[static_cast<std::size_t>(upper)];
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const Eigen::Vector3d x = mesh.face_centre(f);
      const Eigen::Vector3d n = -mesh.area(f).normalized();  // out of the fin
      const int side = std::abs(n.y()) < 0.2 ? 0 : (n.y() > 0 ? 1 : -1);
      s.faces.push_back(
          {x.x(), -x.z(), side, m.rho * flow.p.cells[static_cast<std::size_t>(mesh.owner(f))]});
    }
  }
  return s;
}

void CfdPlant::write_fields(const std::filesystem::path& vtu) const {
  const auto& m = *impl_;
  const auto& mesh = m.sys->mesh();
  const auto& overset = m.sys->overset();
  const auto& flow = *m.flow;
  const auto n = static_cast<std::size_t>(mesh.cells());
  std::map<std::string, std::vector<double>> fields;
  auto& U = fields["U"];
  auto& U_rel = fields["U_rel"];
  auto& p = fields["p"];
  auto& status = fields["status"];
  U.reserve(3 * n);
  U_rel.reserve(3 * n);
  std::vector<Eigen::Matrix3d> axes;  // per component: its axes in the body's
  for (const auto& a : m.sys->component_axes()) axes.push_back(a.linear());
  for (int c = 0; c < mesh.cells(); ++c) {  // 3.
    const auto k = static_cast<std::size_t>(overset.component_of(c));
    const Eigen::Vector3d u = flow.U.cell(c);
    const Eigen::Vector3d body = axes[k] * u;
    const Eigen::Vector3d rel = axes[k] * (u - flow.motion()[k].at(mesh.centre(c)));
    U.insert(U.end(), body.data(), body.data() + 3);
    U_rel.insert(U_rel.end(), rel.data(), rel.data() + 3);
    p.push_back(m.rho * flow.p.cells[static_cast<std::size_t>(c)]);
    status.push_back(static_cast<double>(overset.status(c)));
  }
  if (const auto* model = flow.turbulence())
    for (const auto* field : model->fields()) fields[field->name] = field->cells;
  if (vtu.has_parent_path()) std::filesystem::create_directories(vtu.parent_path());
  mesher::write_vtu(vtu, m.sys->placed_grid(), fields);
}

}  // namespace auvloop::engine

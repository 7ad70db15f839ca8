// SPDX-License-Identifier: GPL-3.0-or-later
// actuator-disk (issue 18, item 2; validation.hpp): the propeller's body-force disk
// (fv::DiskForce, the Hough-Ordway loading of engine/propeller.hpp) in a uniform stream,
// against annular momentum theory.
//   1. a box x in [-upstream, downstream], y and z in [-half_width, half_width] (m): a uniform
//      core of cubes of side h over |x| <= 2 R and |y|, |z| <= 1.5 R, nodes on x = 0 and the
//      axis planes, cells growing by `growth` outwards (the last one of a side stretched to
//      fit);
//   2. the stream U along +x: U fixed at the inlet x = -upstream, p = 0 at the outlet, slip on
//      the four sides; laminar, nu; steady SIMPLE from the uniform stream until the disk speed
//      changes by less than 1e-9 U a step (or max_iterations);
//   3. the disk at the origin, thrust axis -x (the vehicle heads into the stream; the fluid is
//      pushed aft, along +x), tip radius R, hub radius R_H, thickness 2 h, thrust T fixed and no
//      torque (the swirl leaves the axial momentum balance alone at this order);
//   4. the reference: per annulus, annular momentum theory's 2 U^2 a (1 + a) = dT/dA = f_x(r)
//      2 h (the loading of propeller.hpp's continuous distribution), so a(r) =
//      (sqrt(1 + 2 dT/dA / U^2) - 1) / 2, and the disk speed U (1 + a_mean) with a_mean the mean
//      of a(r) over the disk cells weighted by their volumes (what disk_speed measures); and the
//      operating point's own correction u_i = T / (2 u_d A) (propeller.hpp) beside it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/fv/propeller_disk.hpp"
#include "auvloop/engine/validation.hpp"
#include "auvloop/mesher/generators.hpp"

namespace auvloop::engine::validation {

namespace {
// Nodes from 0 to `end` (> 0): uniform h up to `core`, then growing by `growth` (the last cell
// stretched or merged to end exactly on `end`).
std::vector<double> half_nodes(double h, double core, double end, double growth) {
  std::vector<double> x{0};
  const int n = std::max(1, static_cast<int>(std::lround(core / h)));
  for (int i = 1; i <= n; ++i) x.push_back(i * h);
  double d = h;
  while (x.back() < end - 1e-12) {
    d *= growth;
    if (x.back() + 1.5 * d >= end) {
      x.push_back(end);
      break;
    }
    x.push_back(x.back() + d);
  }
  return x;
}

std::vector<double> nodes(double h, double core_lo, double core_hi, double lo, double hi,
                          double growth) {
  auto left = half_nodes(h, core_lo, -lo, growth);
  const auto right = half_nodes(h, core_hi, hi, growth);
  std::vector<double> x;
  for (auto it = left.rbegin(); it != left.rend(); ++it) x.push_back(-*it);
  x.insert(x.end(), right.begin() + 1, right.end());
  return x;
}
}  // namespace

ActuatorDiskResult actuator_disk(const ActuatorDiskCase& c) {
  const auto t0 = std::chrono::steady_clock::now();
  const double R = c.radius, h = c.cell;
  mesher::BoxPatches patches;
  patches.names = {"inlet", "outlet", "side_y0", "side_y1", "side_z0", "side_z1"};
  patches.types = {mesher::PatchType::inlet,    mesher::PatchType::outlet,
                   mesher::PatchType::symmetry, mesher::PatchType::symmetry,
                   mesher::PatchType::symmetry, mesher::PatchType::symmetry};
  const auto grid = mesher::cartesian_box(
      nodes(h, 2 * R, 2 * R, -c.upstream, c.downstream, c.growth),  // 1.
      nodes(h, 1.5 * R, 1.5 * R, -c.half_width, c.half_width, c.growth),
      nodes(h, 1.5 * R, 1.5 * R, -c.half_width, c.half_width, c.growth), patches);
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;  // 2.
  s.nu = c.nu;
  s.steady = true;
  s.dt = 1;  // a label: steady
  s.max_courant = 1e30;
  s.relax_u = 0.7;
  s.relax_p = 0.3;
  s.convection = fv::Convection::linear_upwind;
  fv::Pimple flow(mesh, s);
  flow.U.fix(mesh, "inlet", {c.speed, 0, 0});
  flow.p.fix(mesh, "outlet", 0.0);
  for (const char* side : {"side_y0", "side_y1", "side_z0", "side_z1"}) flow.slip(side);
  for (auto& u : flow.U.c[0].cells) u = c.speed;
  PropellerDisk disk;  // 3.
  disk.axis = -Eigen::Vector3d::UnitX();
  disk.radius = R;
  disk.hub_radius = c.hub_radius;
  disk.thickness = 2 * h;
  const fv::DiskForce force(mesh, disk);
  flow.body_force.assign(static_cast<std::size_t>(mesh.cells()), Eigen::Vector3d::Zero());
  force.apply(c.thrust, 0, flow.body_force);
  flow.initialise();
  ActuatorDiskResult r;
  r.cells = mesh.cells();
  r.disk_cells = static_cast<int>(force.cells().size());
  // The stream's speed through the disk: along -axis (disk_speed measures along the thrust).
  double last = -force.disk_speed(flow.U);
  for (int it = 1; it <= c.max_iterations; ++it) {
    (void)flow.step();
    const double ud = -force.disk_speed(flow.U);
    r.iterations = it;
    r.last_change = std::abs(ud - last);
    last = ud;
    if (it > 10 && r.last_change < 1e-9 * c.speed) break;
  }
  r.disk_speed = last;
  // The same through the disk's mid-plane x = 0 from the face fluxes (the flux the continuity
  // equation sees; the cell velocities beside a concentrated force may differ from it).
  double flux = 0, face_area = 0;
  for (int f = 0; f < mesh.internal_faces(); ++f) {
    const Eigen::Vector3d& xf = mesh.face_centre(f);
    const double rf = std::hypot(xf.y(), xf.z());
    if (std::abs(xf.x()) > 1e-9 * R || rf < c.hub_radius || rf > R) continue;
    const double sign = mesh.area(f).x() > 0 ? 1.0 : -1.0;
    flux += sign * flow.phi[static_cast<std::size_t>(f)];
    face_area += mesh.area(f).norm();
  }
  r.face_speed = face_area > 0 ? flux / face_area : 0.0;
  // 4. (the loading at each disk cell's centre, as the disk samples it)
  const double U = c.speed;
  double a_sum = 0, volume = 0;
  for (int cell : force.cells()) {
    const double dTdA = hough_ordway(disk, c.thrust, 0, mesh.centre(cell)).norm() * disk.thickness;
    const double a = 0.5 * (std::sqrt(1 + 2 * dTdA / (U * U)) - 1);
    a_sum += mesh.volume(cell) * a;
    volume += mesh.volume(cell);
  }
  r.theory_speed = U * (1 + a_sum / volume);
  const double area = std::numbers::pi * (R * R - c.hub_radius * c.hub_radius);
  r.light_loading_induction = c.thrust / (2 * r.disk_speed * area);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace auvloop::engine::validation

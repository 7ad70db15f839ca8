// SPDX-License-Identifier: GPL-3.0-or-later
// Exact checkpoint and restart of a Pimple run (docs/cfd.md, "Checkpoint and restart"): every
// value a step reads besides the settings and boundary conditions, in binary (IEEE doubles as
// stored in memory, so a restart continues bitwise), behind a versioned header:
//   "AUVLFVCK" | u32 version | i32 cells | i32 faces | i32 boundary faces | i32 steps
//   | f64 time | f64 dt | f64 dt_old
//   | U (3 x cells, 3 x boundary) | p (cells, boundary) | phi (faces)
//   | U^n, U^{n-1} (3 x cells each) | phi^n, phi^{n-1} (faces each)
//   | 3 x (i32 n | predictor force component, n = cells or 0)   (version 2)
//   | i32 arrays | arrays x (i32 n | n values): the turbulence model's state(), 0 arrays
//     without a model                                             (version 3; 2 is read as 0)
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "auvloop/engine/fv/pimple.hpp"
#include "auvloop/engine/state_archive.hpp"
#include "auvloop/geometry/file_io.hpp"

namespace auvloop::engine::fv {

namespace {
constexpr char kMagic[8] = {'A', 'U', 'V', 'L', 'F', 'V', 'C', 'K'};
constexpr std::uint32_t kVersion = 3;

void expect_equal(const StateReader& r, const char* what, std::int32_t stored, int actual) {
  if (stored != actual)
    r.fail(fmt::format("written for {} {}, this grid has {}", stored, what, actual));
}
}  // namespace

void Pimple::write_checkpoint(const std::filesystem::path& file) const {
  StateWriter out;
  write_checkpoint(out);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, out.bytes());
}

void Pimple::read_checkpoint(const std::filesystem::path& file) {
  StateReader r(read_file_text(file), file.string());
  read_checkpoint(r, true);
}

void Pimple::write_checkpoint(StateWriter& out) const {
  out.put(kMagic);
  out.put(kVersion);
  out.put(static_cast<std::int32_t>(mesh_.cells()));
  out.put(static_cast<std::int32_t>(mesh_.faces()));
  out.put(static_cast<std::int32_t>(mesh_.boundary_faces()));
  out.put(static_cast<std::int32_t>(steps_));
  out.put(time_);
  out.put(dt_);
  out.put(dt_old_);
  for (const auto& c : U.c) out.raw(c.cells);
  for (const auto& c : U.c) out.raw(c.boundary);
  out.raw(p.cells);
  out.raw(p.boundary);
  out.raw(phi);
  for (const auto& level : U_old_)
    for (const auto& c : level) out.raw(c);
  for (const auto& level : phi_old_) out.raw(level);
  for (const auto& force : predictor_force_) {
    out.put(static_cast<std::int32_t>(force.size()));
    out.raw(force);
  }
  const auto state = turbulence_ ? turbulence_->state() : std::vector<std::vector<double>*>{};
  out.put(static_cast<std::int32_t>(state.size()));
  for (const auto* a : state) {
    out.put(static_cast<std::int32_t>(a->size()));
    out.raw(*a);
  }
}

void Pimple::read_checkpoint(StateReader& r, bool whole) {
  const auto magic = r.get<std::array<char, 8>>();
  if (std::memcmp(magic.data(), kMagic, sizeof(kMagic)) != 0)
    r.fail("not an auvloop flow checkpoint");
  const auto version = r.get<std::uint32_t>();
  if (version != kVersion && version != 2)
    r.fail(fmt::format("version {}, this build reads versions 2 and {}", version, kVersion));
  expect_equal(r, "cells", r.get<std::int32_t>(), mesh_.cells());
  expect_equal(r, "faces", r.get<std::int32_t>(), mesh_.faces());
  expect_equal(r, "boundary faces", r.get<std::int32_t>(), mesh_.boundary_faces());
  // Read into copies so that a truncated file leaves the solver as it was.
  const auto steps = r.get<std::int32_t>();
  const auto time = r.get<double>(), dt = r.get<double>(), dt_old = r.get<double>();
  VectorField u = U;
  ScalarField pressure = p;
  auto flux = phi;
  auto u_old = U_old_;
  auto flux_old = phi_old_;
  for (auto& c : u.c) r.raw(c.cells);
  for (auto& c : u.c) r.raw(c.boundary);
  r.raw(pressure.cells);
  r.raw(pressure.boundary);
  r.raw(flux);
  for (auto& level : u_old)
    for (auto& c : level) r.raw(c);
  for (auto& level : flux_old) r.raw(level);
  auto forces = predictor_force_;
  for (auto& force : forces) {
    const auto size = r.get<std::int32_t>();
    if (size != 0) expect_equal(r, "cells (predictor force)", size, mesh_.cells());
    force.assign(static_cast<std::size_t>(size), 0.0);
    r.raw(force);
  }
  const auto state = turbulence_ ? turbulence_->state() : std::vector<std::vector<double>*>{};
  const auto arrays = version >= 3 ? r.get<std::int32_t>() : 0;
  if (arrays != static_cast<std::int32_t>(state.size()))
    r.fail(fmt::format(
        "{} turbulence-model arrays stored, the flow's model {} ({}); attach the same model "
        "before reading",
        arrays, turbulence_ ? "has" : "is laminar: it has", state.size()));
  std::vector<std::vector<double>> values(state.size());
  for (std::size_t i = 0; i < state.size(); ++i) {
    expect_equal(r, "values (turbulence state)", r.get<std::int32_t>(),
                 static_cast<int>(state[i]->size()));
    values[i].assign(state[i]->size(), 0.0);
    r.raw(values[i]);
  }
  if (whole) r.expect_end();  // before anything changes
  for (std::size_t i = 0; i < state.size(); ++i) *state[i] = std::move(values[i]);
  U = std::move(u);
  p = std::move(pressure);
  phi = std::move(flux);
  U_old_ = std::move(u_old);
  phi_old_ = std::move(flux_old);
  predictor_force_ = std::move(forces);
  steps_ = steps;
  time_ = time;
  dt_ = dt;
  dt_old_ = dt_old;
}

}  // namespace auvloop::engine::fv

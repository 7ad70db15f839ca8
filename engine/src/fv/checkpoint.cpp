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
#include "auvloop/geometry/file_io.hpp"

namespace auvloop::engine::fv {

namespace {
constexpr char kMagic[8] = {'A', 'U', 'V', 'L', 'F', 'V', 'C', 'K'};
constexpr std::uint32_t kVersion = 3;

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
void put(std::string& out, const std::vector<double>& v) {
  if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

class Reader {
 public:
  Reader(std::string data, std::string file) : data_(std::move(data)), file_(std::move(file)) {}
  template <class T>
  T get() {
    T v;
    take(&v, sizeof(T));
    return v;
  }
  void get(std::vector<double>& v) { take(v.data(), v.size() * sizeof(double)); }
  void expect_end() const {
    if (pos_ != data_.size())
      throw std::runtime_error(
          fmt::format("checkpoint {}: {} bytes beyond the data", file_, data_.size() - pos_));
  }
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  void take(void* to, std::size_t n) {
    if (data_.size() - pos_ < n)
      throw std::runtime_error(fmt::format("checkpoint {}: truncated at byte {}", file_, pos_));
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not see
    std::memcpy(to, data_.data() + pos_, n);
    pos_ += n;
  }
  std::string data_, file_;
  std::size_t pos_ = 0;
};

void expect_equal(const Reader& r, const char* what, std::int32_t stored, int actual) {
  if (stored != actual)
    throw std::runtime_error(fmt::format("checkpoint {}: written for {} {}, this grid has {}",
                                         r.file(), stored, what, actual));
}
}  // namespace

void Pimple::write_checkpoint(const std::filesystem::path& file) const {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kVersion);
  put(out, static_cast<std::int32_t>(mesh_.cells()));
  put(out, static_cast<std::int32_t>(mesh_.faces()));
  put(out, static_cast<std::int32_t>(mesh_.boundary_faces()));
  put(out, static_cast<std::int32_t>(steps_));
  put(out, time_);
  put(out, dt_);
  put(out, dt_old_);
  for (const auto& c : U.c) put(out, c.cells);
  for (const auto& c : U.c) put(out, c.boundary);
  put(out, p.cells);
  put(out, p.boundary);
  put(out, phi);
  for (const auto& level : U_old_)
    for (const auto& c : level) put(out, c);
  for (const auto& level : phi_old_) put(out, level);
  for (const auto& force : predictor_force_) {
    put(out, static_cast<std::int32_t>(force.size()));
    put(out, force);
  }
  const auto state = turbulence_ ? turbulence_->state() : std::vector<std::vector<double>*>{};
  put(out, static_cast<std::int32_t>(state.size()));
  for (const auto* a : state) {
    put(out, static_cast<std::int32_t>(a->size()));
    put(out, *a);
  }
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, out);
}

void Pimple::read_checkpoint(const std::filesystem::path& file) {
  Reader r(read_file_text(file), file.string());
  char magic[8];
  for (char& m : magic) m = r.get<char>();
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
    throw std::runtime_error(fmt::format("{} is not an auvloop flow checkpoint", file.string()));
  const auto version = r.get<std::uint32_t>();
  if (version != kVersion && version != 2)
    throw std::runtime_error(
        fmt::format("checkpoint {}: version {}, this build reads versions 2 and {}", file.string(),
                    version, kVersion));
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
  for (auto& c : u.c) r.get(c.cells);
  for (auto& c : u.c) r.get(c.boundary);
  r.get(pressure.cells);
  r.get(pressure.boundary);
  r.get(flux);
  for (auto& level : u_old)
    for (auto& c : level) r.get(c);
  for (auto& level : flux_old) r.get(level);
  auto forces = predictor_force_;
  for (auto& force : forces) {
    const auto size = r.get<std::int32_t>();
    if (size != 0) expect_equal(r, "cells (predictor force)", size, mesh_.cells());
    force.assign(static_cast<std::size_t>(size), 0.0);
    r.get(force);
  }
  const auto state = turbulence_ ? turbulence_->state() : std::vector<std::vector<double>*>{};
  const auto arrays = version >= 3 ? r.get<std::int32_t>() : 0;
  if (arrays != static_cast<std::int32_t>(state.size()))
    throw std::runtime_error(fmt::format(
        "checkpoint {}: {} turbulence-model arrays stored, the flow's model {} ({}); attach the "
        "same model before reading",
        file.string(), arrays, turbulence_ ? "has" : "is laminar: it has", state.size()));
  std::vector<std::vector<double>> values(state.size());
  for (std::size_t i = 0; i < state.size(); ++i) {
    expect_equal(r, "values (turbulence state)", r.get<std::int32_t>(),
                 static_cast<int>(state[i]->size()));
    values[i].assign(state[i]->size(), 0.0);
    r.get(values[i]);
  }
  r.expect_end();
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

// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/field.hpp"

#include <stdexcept>

namespace auvloop::engine::fv {

int patch_index(const Mesh& mesh, const std::string& name) {
  const auto& patches = mesh.grid().patches;
  std::string known;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    if (patches[p].name == name) return static_cast<int>(p);
    known += (known.empty() ? "" : ", ") + patches[p].name;
  }
  throw std::invalid_argument("grid '" + mesh.grid().name + "' has no patch '" + name +
                              "' (patches: " + known + ")");
}

ScalarField::ScalarField(const Mesh& mesh, std::string field_name)
    : name(std::move(field_name)),
      cells(static_cast<std::size_t>(mesh.cells()), 0.0),
      boundary(static_cast<std::size_t>(mesh.boundary_faces()), 0.0) {
  for (const auto& patch : mesh.grid().patches) {
    bcs.push_back(
        {patch.type == mesher::PatchType::empty ? BcKind::empty : BcKind::zero_gradient, {}});
  }
}

namespace {
std::size_t settable_patch(const Mesh& mesh, const std::string& patch) {
  const auto p = static_cast<std::size_t>(patch_index(mesh, patch));
  if (mesh.grid().patches[p].type == mesher::PatchType::periodic)
    throw std::invalid_argument("patch '" + patch + "' of grid '" + mesh.grid().name +
                                "' is periodic: its values are those of the coupled cells");
  return p;
}
}  // namespace

void ScalarField::fix(const Mesh& mesh, const std::string& patch, double v) {
  const auto p = settable_patch(mesh, patch);
  bcs[p].kind = BcKind::fixed_value;
  bcs[p].value.assign(static_cast<std::size_t>(mesh.grid().patches[p].size), v);
  bcs[p].fraction.clear();
}

void ScalarField::mix(const Mesh& mesh, const std::string& patch, double v) {
  const auto p = settable_patch(mesh, patch);
  bcs[p].kind = BcKind::mixed;
  bcs[p].value.assign(static_cast<std::size_t>(mesh.grid().patches[p].size), v);
  bcs[p].fraction.assign(static_cast<std::size_t>(mesh.grid().patches[p].size), 0.0);
}

void ScalarField::update_boundary(const Mesh& mesh) {
  const auto& patches = mesh.grid().patches;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    for (int i = 0; i < patches[p].size; ++i) {
      const int f = patches[p].start + i;
      const auto b = static_cast<std::size_t>(f - mesh.internal_faces());
      const auto is = static_cast<std::size_t>(i);
      const double inner = cells[static_cast<std::size_t>(mesh.owner(f))];
      if (bcs[p].kind == BcKind::fixed_value) {
        boundary[b] = bcs[p].value[is];
      } else if (bcs[p].kind == BcKind::mixed) {
        const double w = bcs[p].fraction[is];
        boundary[b] = w * bcs[p].value[is] + (1 - w) * inner;
      } else {
        boundary[b] = inner;
      }
    }
  }
}

std::array<double, 2> ScalarField::value_coeffs(const Mesh& mesh, int b) const {
  const auto p = static_cast<std::size_t>(mesh.patch_of(b));
  const auto kind = bcs[p].kind;
  if (kind != BcKind::fixed_value && kind != BcKind::mixed) return {1.0, 0.0};
  const auto i = static_cast<std::size_t>(b + mesh.internal_faces() - mesh.grid().patches[p].start);
  if (kind == BcKind::fixed_value) return {0.0, bcs[p].value[i]};
  const double w = bcs[p].fraction[i];
  return {1 - w, w * bcs[p].value[i]};
}

VectorField::VectorField(const Mesh& mesh, const std::string& name)
    : c{ScalarField(mesh, name + "x"), ScalarField(mesh, name + "y"),
        ScalarField(mesh, name + "z")} {}

void VectorField::fix(const Mesh& mesh, const std::string& patch, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) c[static_cast<std::size_t>(i)].fix(mesh, patch, v[i]);
}

void VectorField::update_boundary(const Mesh& mesh) {
  for (auto& comp : c) comp.update_boundary(mesh);
}

}  // namespace auvloop::engine::fv

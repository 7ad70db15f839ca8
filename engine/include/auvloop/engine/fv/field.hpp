// SPDX-License-Identifier: GPL-3.0-or-later
// Scalar fields on a fv::Mesh: one value per cell and one per boundary face, and the boundary
// condition of each patch. A vector field (velocity) is three scalar components that share one
// matrix; conditions that couple components (slip) are applied by refreshing fixed values.
//
// Every condition is linear in the owner cell value, phi_b = a phi_P + b, which is how the
// operators take it implicitly:
//   fixed_value    phi_b = value (wall, moving wall, inlet, pressure outlet):  a = 0, b = value
//   zero_gradient  phi_b = phi_P (outflow velocity, wall pressure):          a = 1, b = 0
//   empty          the out-of-plane faces of 2D grids: no flux of any kind; phi_b = phi_P only so
//                  that gradients see a zero out-of-plane derivative.
//   mixed          per face phi_b = f value + (1 - f) phi_P, the value fraction f in [0, 1]
//                  (OpenFOAM's mixed): a = 1 - f, b = f value. A far field (Pimple::far_field)
//                  switches its faces between fixed (f = 1) and zero gradient (f = 0).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "auvloop/engine/fv/mesh.hpp"

namespace auvloop::engine::fv {

enum class BcKind { fixed_value, zero_gradient, empty, mixed };

struct PatchBc {
  BcKind kind = BcKind::zero_gradient;
  std::vector<double> value;     // per face of the patch (fixed_value, mixed)
  std::vector<double> fraction;  // per face of the patch: the value fraction f (mixed only)
};

struct ScalarField {
  std::string name;
  std::vector<double> cells;
  std::vector<double> boundary;  // per boundary face
  std::vector<PatchBc> bcs;      // per patch of the grid

  // Zero field with zero-gradient patches (empty patches stay empty).
  ScalarField(const Mesh& mesh, std::string field_name);
  ScalarField() = default;

  // Fixed value `v` on every face of patch `patch` (by name); throws if there is no such patch.
  void fix(const Mesh& mesh, const std::string& patch, double v);
  // A mixed condition on patch `patch` (by name): every face zero gradient with value `v` until
  // its fraction is set; throws if there is no such patch or it is periodic.
  void mix(const Mesh& mesh, const std::string& patch, double v);
  // Re-evaluates the boundary values from the cells (zero gradient, empty) and fixed values.
  void update_boundary(const Mesh& mesh);
  // The coefficients (a, b) of phi_b = a phi_P + b for boundary face b.
  [[nodiscard]] std::array<double, 2> value_coeffs(const Mesh& mesh, int b) const;
  // Whether boundary face b's value is the fixed one (a = 0: fixed_value, or mixed with f = 1).
  [[nodiscard]] bool fixes(const Mesh& mesh, int b) const {
    return value_coeffs(mesh, b)[0] == 0.0;
  }
  [[nodiscard]] bool is_empty(const Mesh& mesh, int b) const {
    return bcs[static_cast<std::size_t>(mesh.patch_of(b))].kind == BcKind::empty;
  }
};

struct VectorField {
  std::array<ScalarField, 3> c;
  VectorField(const Mesh& mesh, const std::string& name);
  VectorField() = default;
  // Fixed vector value on a patch (walls, moving walls, inlets).
  void fix(const Mesh& mesh, const std::string& patch, const Eigen::Vector3d& v);
  void update_boundary(const Mesh& mesh);
  [[nodiscard]] Eigen::Vector3d cell(int i) const {
    const auto s = static_cast<std::size_t>(i);
    return {c[0].cells[s], c[1].cells[s], c[2].cells[s]};
  }
  [[nodiscard]] Eigen::Vector3d face(int b) const {
    const auto s = static_cast<std::size_t>(b);
    return {c[0].boundary[s], c[1].boundary[s], c[2].boundary[s]};
  }
};

// Index of the patch called `name`; throws std::invalid_argument naming the grid's patches.
int patch_index(const Mesh& mesh, const std::string& name);

}  // namespace auvloop::engine::fv

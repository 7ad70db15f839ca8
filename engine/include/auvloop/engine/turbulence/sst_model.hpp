// SPDX-License-Identifier: GPL-3.0-or-later
// Menter's SST k-omega model (2003; sst.hpp has its point functions) as a fv::TurbulenceModel:
// k and omega transported on the finite-volume operators of the momentum equation, the eddy
// viscosity nu_t, and the wall treatment for any y+ (wall_treatment.hpp). Incompressible:
//   ddt(omega) + div(phi, omega) - Sp(div phi) omega - laplacian(nu + sigma_w nu_t, omega)
//       == gamma S^2 - Sp(beta omega) omega + (1 - F1) 2 sigma_w2 grad(k) . grad(omega) / omega
//   ddt(k) + div(phi, k) - Sp(div phi) k - laplacian(nu + sigma_k nu_t, k)
//       == min(nu_t S^2, 10 beta* k omega) - Sp(beta* omega) k
//   nu_t = a1 k / max(a1 omega, S F2)
// with S^2 = 2 S_ij S_ij, sigma, beta and gamma blended by F1, F1 and F2 from the wall distance.
// The omega production is gamma S^2 (Menter, Kuntz and Langtry 2003), which is gamma P / nu_t
// with the unlimited P; OpenFOAM v1912 caps it consistently with the k limiter (its GbyNu), a
// difference only where the limiter acts (the limited_cells count of the report).
//
// One correct() (the PIMPLE hook after the pressure correctors, turbulence_model.hpp):
//   1. the cell gradients of U (the flow's, TurbulenceInput::grad_U), k and omega; S^2 per cell;
//      F1 with the current k, omega;
//   2. the wall treatment per wall face f with first cell P: the wall-parallel speed U_t of P
//      relative to the wall at the face-normal distance y of its centre, u_tau from Spalding's
//      law, y+ = y u_tau / nu; the first cell's target omega wall_omega(y, u_tau), its weight
//      roughness_share(menter_roughness(2 y+)) and its k production wall_production(y+, u_tau)
//      (each averaged over the cell's wall faces; how they enter: WallTreatment below);
//   3. the omega equation (bounded TVD convection, implicit destruction, the cross-diffusion
//      term explicit where it is positive and implicit where it is negative), under-relaxed in
//      all but the final outer iteration (every iteration when steady), solved, bounded below;
//   4. the k equation likewise (its wall-cell production from step 2); k at walls zero
//      gradient (the wall treatment supplies its production for any y+); with
//      SstSettings::ambient_sources, beta omega_amb^2 and beta* omega_amb k_amb added to the
//      omega and k sources (wall cells' k production excepted: the wall treatment's);
//   5. nu_t per cell with F2 from the new k, omega; per internal face by linear interpolation;
//      per wall face the wall function's nu_t,w = max(0, u_tau^2 y / U_t - nu), so the
//      momentum equation's wall flux (nu + nu_t,w) U_t / y is the law-of-the-wall shear
//      u_tau^2 at any y+ (nu_t,w = 0 in the viscous sublayer: the no-slip wall of a resolved
//      boundary layer).
// Positivity (engine/src/turbulence/positivity.hpp; docs/cfd.md, "Positivity"): a negative
// net explicit source is taken implicitly as a rate -source / ref_c with ref_c = phi_c, except at
// a local minimum, where ref_c is at least its neighbours' mean; after the solve the bound raises
// a cell's k below k_min or omega below omega_min to its neighbours' mean (each at least the
// floor; OpenFOAM's bound()) and counts the cells it changed (TurbulenceReport::bounded_cells):
// with bounded convection and implicit destruction it should act rarely, and a report that it
// acts often says the solution is in trouble. Free-stream values at inlets, zero gradient at
// outlets and symmetry planes.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "auvloop/engine/fv/turbulence_model.hpp"
#include "auvloop/engine/turbulence/sst.hpp"
#include "auvloop/engine/turbulence/wall_treatment.hpp"

namespace auvloop::engine::turbulence {

// How walls are treated (step 2 and the wall rows of steps 3-5):
// - `any_y_plus` (the default): Menter's wall-face omega = 10 * 6 nu / (beta1 d1^2) (d1 the first
//   cell's height) is always set, and the first cell's omega is drawn towards the wall-function
//   value wall_omega(y, u_tau) with the weight w = roughness_share(menter_roughness(d1+))
//   (Matrix::pull_values; wall_treatment.hpp): Menter's value amounts to a sand-grain roughness
//   ks+ = 1.768 d1+, so where it is hydraulically smooth (ks+ <= 2.25, y+ below about 0.64) the
//   first cell keeps its own equation (the TMR's treatment), where it would be fully rough (ks+
//   >= 90, y+ above about 25) the wall-function value is fixed, and in between the weight is the
//   share of the roughness' effect the wall-function value takes away; k zero gradient, the wall
//   production and nu_t,w from the law of the wall;
// - `wall_function`: the first cell's omega fixed to wall_omega(y, u_tau) at every y+ (OpenFOAM's
//   omegaWallFunction), otherwise as any_y_plus (k zero gradient, production and nu_t,w from the
//   law); accurate from y+ of about 5 (the peer comparison uses it);
// - `resolved`: the TMR's wall values, k = 0 and Menter's omega on the wall face, no-slip wall
//   flux and the model's own production: only for y+ below about 1.
enum class WallTreatment { any_y_plus, wall_function, resolved };

struct SstSettings {
  SstConstants constants;
  LawOfTheWall law;
  double nu = 1e-6;       // kinematic viscosity (m^2/s): the flow's
  FreeStream freestream;  // inlet values and the initial fields
  fv::Convection convection = fv::Convection::van_leer_skew;  // bounded (TVD)
  fv::AsymmetricMethod solver = fv::AsymmetricMethod::bicgstab_jacobi;
  double tolerance = 1e-8;  // linear solves of k and omega (the flow's residual norm)
  double relax = 0.7;       // under-relaxation of k and omega (not in a transient's final
                            // outer iteration)
  double floor = 1e-15;     // k_min and omega_min as this fraction of the free-stream values
  WallTreatment wall = WallTreatment::any_y_plus;
  // Ambient sources (Spalart and Rumsey 2007, NASA TMR's "SST-sust"; OpenFOAM's decayControl):
  // + beta* omega_amb k_amb in the k equation and + beta omega_amb^2 in the omega equation, with
  // the free stream as the ambient values, so that the free stream holds its level instead of
  // decaying (a body towed through water at rest, where nothing renews it). Off by default.
  bool ambient_sources = false;
};

// The achieved y+ of the first cells on one wall patch (the solver's report, item 4).
struct WallYPlus {
  std::string patch;
  int faces = 0;
  double min = 0, mean = 0, max = 0;  // mean: area-weighted
};

class SstModel final : public fv::TurbulenceModel {
 public:
  // `wall_distance`: per cell of `mesh` (WallDistances::of). Throws std::invalid_argument if its
  // size is not the mesh's, a setting is out of range, or the free stream is not positive.
  SstModel(const fv::Mesh& mesh, std::vector<double> wall_distance, SstSettings settings);

  fv::ScalarField k;      // m^2/s^2
  fv::ScalarField omega;  // 1/s
  fv::ScalarField nu_t;   // m^2/s; boundary: per face, walls from the wall treatment

  // The wall distance after the grids moved relative to each other (WallDistances::update), read
  // from the next correct() on; throws std::invalid_argument as the constructor.
  void set_wall_distance(std::span<const double> wall_distance);
  // Free-stream k and omega fixed on a patch (an inlet).
  void inlet(const std::string& patch);
  // A far field (Pimple::far_field's patches; OpenFOAM's inletOutlet): face by face, free-stream
  // k and omega where the flux relative to the grid enters the domain (phi <= 0), zero gradient
  // where it leaves, switched by the flux at every correct(), so that a box turning with the
  // vehicle takes the free stream on the faces that face the flow.
  void far_field(const std::string& patch);
  // Initial cell values for initialise() instead of the free stream (a restart from another
  // solution, grid sequencing); one per cell each, positive.
  void start_from(std::vector<double> k0, std::vector<double> omega0);

  void initialise(const fv::VectorField& U, std::span<const double> phi) override;
  void begin_step() override;
  [[nodiscard]] std::span<const double> nu_eff() const override { return nu_eff_; }
  fv::TurbulenceReport correct(const fv::TurbulenceInput& input) override;
  void save() override;
  void restore() override;
  void check() const override;
  [[nodiscard]] std::vector<const fv::ScalarField*> fields() const override {
    return {&k, &omega, &nu_t};
  }
  [[nodiscard]] std::vector<fv::ScalarField*> fields() override { return {&k, &omega, &nu_t}; }
  [[nodiscard]] std::vector<std::vector<double>*> state() override {
    return {&k.cells,   &k.boundary, &omega.cells,   &omega.boundary, &nu_t.cells, &nu_t.boundary,
            &k_old_[0], &k_old_[1],  &omega_old_[0], &omega_old_[1],  &nu_eff_};
  }

  void set_overset(const fv::Overset* overset) override { overset_ = overset; }
  void carried(std::vector<Carried>& out) override {
    out.assign({{&k.cells, &k_old_[0]}, {&omega.cells, &omega_old_[0]}});
  }

  // Per wall patch, from the last correct() (or initialise()); on an overset mesh the wall faces
  // in the flow (their cell not a hole).
  [[nodiscard]] std::vector<WallYPlus> y_plus() const;
  // Per cell: the blending function F1 of the last correct().
  [[nodiscard]] std::span<const double> f1() const { return F1_; }
  [[nodiscard]] const SstSettings& settings() const { return settings_; }

 private:
  struct WallFace {
    int face = 0, patch = 0;
    int cell = 0;      // index into wall_cells_ of its owner
    double y = 0;      // face-normal distance of the owner's centre (m)
    double u_tau = 0;  // m/s
    double y_plus = 0;
    double u_plus = 0;  // U_t / u_tau
    double nu_t = 0;    // the wall function's nu_t,w (m^2/s)
  };
  void wall_treatment(const fv::VectorField& U);
  void switch_far_field(std::span<const double> phi);
  void update_nu_t();
  void strain(const fv::VectorField& U, const std::array<std::vector<Eigen::Vector3d>, 3>* given);

  // Whether wall face w lies in the flow (no overset mesh, or its cell is not a hole).
  [[nodiscard]] bool in_flow(const WallFace& w) const;

  const fv::Mesh& mesh_;
  const fv::Overset* overset_ = nullptr;
  std::vector<double> fixed_;   // the overset's fixed values of one equation (scratch)
  std::vector<int> far_field_;  // patches
  SstSettings settings_;
  std::vector<double> d_;  // wall distance per cell
  std::vector<WallFace> walls_;
  std::vector<int> wall_cells_;              // ascending, each once
  std::vector<int> wall_faces_;              // per wall cell: its wall faces
  std::vector<double> wall_omega_, wall_G_;  // per wall cell
  std::vector<double> wall_weight_;          // per wall cell: the pull (0 where fixed)
  std::vector<int> rough_cells_;             // wall cells whose weight is 1, ascending
  std::vector<double> rough_omega_;          // their omega
  std::vector<double> S2_, F1_, nu_eff_;
  std::vector<double> ref_;  // positivity.hpp's scratch: the sink references, the bound's values
  std::vector<double> k0_, omega0_;  // start_from()
  std::array<std::vector<double>, 2> k_old_, omega_old_;
  std::vector<std::vector<double>> good_;  // state() at the start of the step
  fv::Matrix eq_;
  std::vector<double> rate_, source_, gamma_;
};

}  // namespace auvloop::engine::turbulence

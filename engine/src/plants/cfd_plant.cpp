// SPDX-License-Identifier: GPL-3.0-or-later
// The CFD plant's advance, steps 1-5 of engine/cfd_plant.hpp.
#include "auvloop/engine/cfd_plant.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "auvloop/mesher/mesh_settings.hpp"
#include "cfd_plant_impl.hpp"

namespace auvloop::engine {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

DfbiBody dfbi_body(const geometry::Vehicle& v, const CfdPlantSettings& s) {
  DfbiBody b;
  b.mass = rigid_body_mass(v.mass.mass, v.mass.cg_from_cb, v.mass.inertia);
  b.added_mass = s.added_mass;
  b.weight = v.mass.weight();
  b.buoyancy = s.neutral_buoyancy ? b.weight : v.mass.buoyancy;
  b.r_g = v.mass.cg_from_cb;
  b.free = s.free;
  b.relax = s.relax;
  return b;
}

void check(const CfdPlantSettings& s) {
  const auto bad = [](const std::string& what) {
    throw std::invalid_argument("CFD plant: " + what);
  };
  if (s.outer_iterations < 1)
    bad(fmt::format("outer_iterations must be at least 1, got {}", s.outer_iterations));
  if (!(s.nu > 0)) bad(fmt::format("the water's viscosity must be positive, got {}", s.nu));
  if (!(s.reference_speed > 0) || !(s.intensity > 0) || !(s.viscosity_ratio > 0))
    bad("the free stream's reference speed, intensity and viscosity ratio must be positive");
  if (s.sense != 1 && s.sense != -1)
    bad(fmt::format("the propeller's sense must be +1 or -1, got {}", s.sense));
  if (!(s.runaway_speed > 0)) bad("runaway_speed must be positive");
  if (s.mesh_settings && !s.mesh_settings->fin_deflections.empty())
    bad("the mesh settings' fin_deflections must be empty: the plant turns the fins");
  if (!(s.max_flow_speed >= 0) || !(s.max_courant >= 0))
    bad("the flow's guards max_flow_speed and max_courant must be at least 0 (0: none)");
  if (s.pressure_correctors < 1)
    bad(fmt::format("pressure_correctors must be at least 1, got {}", s.pressure_correctors));
  if (!(s.tolerance > 0 && s.tolerance < 1))
    bad(fmt::format("tolerance must be in (0, 1), got {}", s.tolerance));
  if (!(s.intermediate_tolerance >= 0 && s.intermediate_tolerance < 1))
    bad(fmt::format("intermediate_tolerance must be in [0, 1), got {}", s.intermediate_tolerance));
}
}  // namespace

CfdPlant::CfdPlant(const geometry::Vehicle& vehicle, CfdPlantSettings settings)
    : impl_(std::make_unique<Impl>()), dfbi_(dfbi_body(vehicle, settings)) {
  check(settings);
  auto& m = *impl_;
  m.vehicle = vehicle;
  m.settings = std::move(settings);
  const auto& s = m.settings;
  if (!m.settings.curve && !vehicle.propeller.open_water.empty()) {
    const auto& w = vehicle.propeller.open_water;
    std::vector<OpenWaterPoint> points;
    for (std::size_t i = 0; i < w.J.size(); ++i) points.push_back({w.J[i], w.KT[i], w.KQ[i]});
    m.settings.curve = [table = OpenWaterTable(std::move(points))](double J) {
      return table.at(J);
    };
  }
  m.rho = vehicle.mass.water_density;
  if (!(m.rho > 0))
    throw std::invalid_argument("CFD plant: the vehicle file gives no water density");
  const auto grids = s.mesh_settings ? *s.mesh_settings : mesher::mesh_preset(s.mesh, vehicle);
  m.grids = mesher::mesh_settings_json(grids);
  m.sys = std::make_unique<fv::VehicleOverset>(mesher::build_grid_system(vehicle, grids), vehicle);
  const auto& mesh = m.sys->mesh();
  fv::PimpleSettings ps;
  ps.nu = s.nu;
  ps.outer_iterations = s.outer_iterations;
  ps.convection = s.convection;
  ps.relax_u = s.relax_u;
  ps.relax_p = s.relax_p;
  ps.pressure_correctors = s.pressure_correctors;
  ps.tolerance = s.tolerance;
  ps.turbulence_final_only = s.turbulence_final_only;
  ps.intermediate_tolerance = s.intermediate_tolerance;
  // The nose rim's and fin roots' tiny cells pass Courant numbers of several hundred at 2 ms
  // and five times that at 10 ms on coarse while the flow stays smooth (measured), more on finer
  // grids: the guard against a runaway is the water's speed.
  ps.max_courant = s.max_courant > 0 ? s.max_courant : std::numeric_limits<double>::infinity();
  ps.max_speed = s.max_flow_speed;
  ps.divergence_directory = s.divergence_directory;
  m.flow = std::make_unique<fv::Pimple>(mesh, ps);
  m.flow->set_overset(&m.sys->overset());
  for (const auto& patch : mesh.grid().patches) {
    if (patch.type == mesher::PatchType::wall) {
      m.flow->wall(patch.name);
      parts_.push_back(patch.name);
    } else if (patch.name.rfind("background/", 0) == 0 &&
               patch.type != mesher::PatchType::overset) {
      m.flow->far_field(patch.name);
    }
  }
  if (s.sst) {
    m.walls = std::make_unique<turbulence::WallDistances>(mesh, m.sys->composite().cell_offset);
    turbulence::SstSettings ts;
    ts.nu = s.nu;
    ts.freestream = turbulence::freestream_from_intensity(s.reference_speed, s.intensity,
                                                          s.viscosity_ratio, s.nu);
    ts.ambient_sources = true;  // a body moving through water at rest (remus-overset-sst)
    ts.solver = fv::AsymmetricMethod::bicgstab_gs;
    m.sst = std::make_unique<turbulence::SstModel>(mesh, m.walls->composite(), ts);
    for (const auto& patch : mesh.grid().patches)
      if (patch.name.rfind("background/", 0) == 0 && patch.type != mesher::PatchType::overset)
        m.sst->far_field(patch.name);
    m.flow->set_turbulence(m.sst.get());
  }
  // The disk on the hull grid's cells in the flow (a fringe or hole cell's force never reaches
  // the flow), with its inflow plane.
  const auto& p = vehicle.propeller;
  PropellerDisk disk;
  disk.centre = Eigen::Vector3d(vehicle.mass.cb_station - p.station, 0, 0);
  disk.radius = 0.5 * p.diameter;
  disk.hub_radius = 0.5 * p.hub_diameter;
  disk.thickness = p.disk_thickness;
  disk.sense = s.sense;
  std::vector<char> hull(static_cast<std::size_t>(mesh.cells()), 0);
  const auto& overset = m.sys->overset();
  for (int c = 0; c < m.sys->composite().cells_of(0); ++c)
    hull[static_cast<std::size_t>(c)] = overset.active(c) ? 1 : 0;
  if (s.propeller)
    m.disk = std::make_unique<fv::DiskForce>(
        mesh, disk, hull, s.inflow_offset < 0 ? 0.25 * p.diameter : s.inflow_offset);
  m.flow->body_force.assign(static_cast<std::size_t>(mesh.cells()), Eigen::Vector3d::Zero());
  m.rates.assign(static_cast<std::size_t>(m.sys->fins()), 0.0);
  reset(BodyState{});
}

CfdPlant::~CfdPlant() = default;

const fv::Pimple& CfdPlant::flow() const {
  return *impl_->flow;
}

int CfdPlant::cells() const {
  return impl_->sys->mesh().cells();
}

void CfdPlant::reset(const BodyState& initial) {
  auto& m = *impl_;
  dfbi_.set_free(m.settings.free);
  dfbi_.reset(initial);
  signals_.assign(signal_columns().size(), std::nan(""));
  clock_.fill(0);
  if (spun_up_ && *spun_up_ == initial.nu) {
    report_ = {};
    return;
  }
  spun_up_.reset();
  if (m.sys->deflections() != std::vector<double>(m.rates.size(), 0.0)) {
    m.sys->set_fins(std::vector<double>(m.rates.size(), 0.0));
    if (m.sst) {
      (void)m.walls->update(m.sys->component_axes(), m.sys->cells_in_flow());
      m.sst->set_wall_distance(m.walls->composite());
    }
  }
  for (auto& c : m.flow->U.c) std::fill(c.cells.begin(), c.cells.end(), 0.0);
  std::fill(m.flow->p.cells.begin(), m.flow->p.cells.end(), 0.0);
  std::fill(m.rates.begin(), m.rates.end(), 0.0);
  std::fill(m.flow->body_force.begin(), m.flow->body_force.end(), Eigen::Vector3d::Zero());
  m.rpm = m.J = m.inflow = m.thrust = m.torque = 0;
  m.move(initial);
  m.flow->initialise();
  report_ = {};
}

int CfdPlant::spin_up_steps(double duration, double dt) {
  const double start = std::min(dt, kStartDt);
  return kStartSteps +
         static_cast<int>(std::lround(std::max(0.0, duration - kStartSteps * start) / dt));
}

std::optional<PlantFailure> CfdPlant::spin_up(const BodyState& initial, double rpm, double duration,
                                              double dt,
                                              const std::function<void(double t)>& progress) {
  spun_up_.reset();
  reset(initial);
  dfbi_.set_free({false, false, false, false, false, false});
  ActuatorValues a;
  a.rpm = rpm;
  const double start = std::min(dt, kStartDt);
  const int steps = spin_up_steps(duration, dt);
  double t = 0;
  for (int n = 0; n < steps; ++n) {
    const double h = n < kStartSteps ? start : dt;
    const auto result = advance(a, h);
    if (const auto* failure = std::get_if<PlantFailure>(&result)) {
      auto out = *failure;
      reset(initial);
      return out;
    }
    t += h;
    if (progress) progress(t);
  }
  spun_up_ = initial.nu;
  dfbi_.set_free(impl_->settings.free);
  return std::nullopt;
}

namespace {
constexpr std::string_view kPlantTag = "cfd plant";
}

void CfdPlant::save(StateWriter& out) const {
  const auto& m = *impl_;
  out.tag(kPlantTag);
  out.put(std::string_view(m.grids));
  const auto& h = dfbi_.history();
  put(out, h.state);
  out.put(h.nu_old);
  out.put(h.acceleration);
  m.sys->save(out);
  if (m.sst) m.walls->save(out);
  out.put(m.rates);
  out.put(spun_up_.has_value());
  out.put(spun_up_.value_or(Vector6d::Zero()));
  out.put(signals_);
  m.flow->write_checkpoint(out);
}

void CfdPlant::load(StateReader& in) {
  auto& m = *impl_;
  in.expect_tag(kPlantTag);
  if (const auto grids = in.get_string(); grids != m.grids)
    in.fail(fmt::format("written on other grids ({}), this plant's are {}", grids, m.grids));
  DfbiHistory h;
  h.state = get_body_state(in);
  in.get(h.nu_old);
  in.get(h.acceleration);
  // The grids and the flow as at the end of the stored step: the assembly (whose statuses
  // initialise() takes as the fields'), the wall distances, the body's motion with the fins'
  // rates, then the fields. Each replaces the present one whole, so unlike reset() the fins do
  // not turn back to zero first (a re-assembly and a wall-distance update for nothing).
  dfbi_.set_free(m.settings.free);
  spun_up_.reset();
  std::fill(m.flow->body_force.begin(), m.flow->body_force.end(), Eigen::Vector3d::Zero());
  m.rpm = m.J = m.inflow = m.thrust = m.torque = 0;
  try {
    m.sys->load(in);
    if (m.sst) {
      m.walls->load(in);
      m.sst->set_wall_distance(m.walls->composite());
    }
    auto rates = in.get_vector();
    if (rates.size() != m.rates.size())
      in.fail(fmt::format("{} fin rates stored, this vehicle has {} fins", rates.size(),
                          m.rates.size()));
    const bool spun = in.get<bool>();
    Vector6d spun_nu;
    in.get(spun_nu);
    auto signals = in.get_vector();
    if (signals.size() != signal_columns().size())
      in.fail(fmt::format("{} recorded signals stored, this plant records {}", signals.size(),
                          signal_columns().size()));
    m.rates = std::move(rates);
    dfbi_.restore(h);
    m.move(h.state);
    m.flow->initialise();
    m.flow->read_checkpoint(in);
    spun_up_ = spun ? std::optional<Vector6d>(spun_nu) : std::nullopt;
    signals_ = std::move(signals);
    clock_.fill(0);
  } catch (const std::runtime_error&) {
    reset(BodyState{});
    throw;
  }
  report_ = {};
}

PlantResult CfdPlant::advance(const ActuatorValues& a, double dt) {
  const auto t0 = std::chrono::steady_clock::now();
  auto& m = *impl_;
  if (!(dt > 0 && std::isfinite(dt)))
    return PlantFailure{fmt::format("CFD plant: time step must be positive, got {}", dt)};
  if (!(a.rpm >= 0 && std::isfinite(a.rpm)))
    return PlantFailure{fmt::format("CFD plant: rpm {} (the disk runs ahead only)", a.rpm)};
  if (a.rpm > 0 && !m.disk)
    return PlantFailure{fmt::format("CFD plant: rpm {}, but the plant has no propeller", a.rpm)};
  if (a.rpm > 0 && !m.settings.curve)
    return PlantFailure{"CFD plant: the propeller turns but has no open-water curve"};
  CfdStepReport r;
  // 1.
  const auto tf = std::chrono::steady_clock::now();
  std::vector<double> deflection;
  for (const auto& fin : m.vehicle.fin_set.fins)
    deflection.push_back(geometry::fin_deflection(fin, a.delta_r, a.delta_s));
  for (std::size_t k = 0; k < deflection.size(); ++k)
    m.rates[k] = (deflection[k] - m.sys->deflections()[k]) / dt;
  if (deflection != m.sys->deflections()) {
    try {
      m.sys->set_fins(deflection);
    } catch (const std::invalid_argument& e) {
      std::fill(m.rates.begin(), m.rates.end(), 0.0);
      return PlantFailure{fmt::format("CFD plant: the fins could not turn to {}: {}",
                                      fmt::join(deflection, ", "), e.what())};
    }
    if (m.sst) {
      (void)m.walls->update(m.sys->component_axes(), m.sys->cells_in_flow());
      m.sst->set_wall_distance(m.walls->composite());
    }
  }
  r.seconds_fins = seconds_since(tf);
  // 2.
  m.rpm = a.rpm;
  m.flow->set_time_step(dt);
  const auto tc = std::chrono::steady_clock::now();
  m.move(dfbi_.begin_step(dt, m.flow->steps() > 0));
  m.propel(dfbi_.iterate());
  r.seconds_coupling = seconds_since(tc);
  // 3.
  m.flow->motion_correct = [&](int) {
    const auto ti = std::chrono::steady_clock::now();
    m.move(dfbi_.correct(m.loads()));
    m.propel(dfbi_.iterate());
    r.seconds_coupling += seconds_since(ti);
  };
  try {
    r.flow = m.flow->step();
  } catch (const fv::DivergenceError& e) {
    m.flow->motion_correct = nullptr;
    return PlantFailure{fmt::format("CFD plant: {}", e.what())};
  }
  m.flow->motion_correct = nullptr;
  // 5.
  dfbi_.accept();
  const auto& s = dfbi_.state();
  r.time = m.flow->time();
  r.rpm = m.rpm;
  r.J = m.J;
  r.inflow_speed = m.inflow;
  r.thrust = m.thrust;
  r.torque = m.torque;
  r.walls = fv::wall_forces(*m.flow);
  for (auto& [name, f] : r.walls) {
    f.pressure *= m.rho;
    f.viscous *= m.rho;
    f.pressure_moment *= m.rho;
    f.viscous_moment *= m.rho;
  }
  r.deflections = m.sys->deflections();
  r.coupling_change = dfbi_.change();
  r.seconds = seconds_since(t0);
  report_ = std::move(r);
  record_signals();
  if (!s.nu.allFinite() || s.nu.head<3>().norm() > m.settings.runaway_speed)
    return PlantFailure{fmt::format("CFD plant: speed {:.3g} m/s beyond the runaway limit {} m/s",
                                    s.nu.head<3>().norm(), m.settings.runaway_speed)};
  return PlantStep{s, dfbi_.acceleration()};
}

namespace {
std::string part_name(const std::string& patch) {  // "hull/hull" -> "hull"
  return patch.substr(0, patch.find('/'));
}
}  // namespace

std::vector<std::pair<std::string, std::string>> CfdPlant::signal_columns() const {
  std::vector<std::pair<std::string, std::string>> c{
      {"J", "-"}, {"V_a", "m/s"}, {"thrust", "N"}, {"torque", "N m"}};
  // The flow solver's step (a CFD engineer's residual log): outer iterations taken, momentum's
  // initial residual in the last of them, the Krylov iterations of pressure, momentum and the
  // SST equations summed over the step, the largest Courant number, the continuity error.
  for (const char* name :
       {"solver.outer", "solver.outer_residual", "solver.p_iterations", "solver.U_iterations",
        "solver.komega_iterations", "solver.courant", "solver.continuity"})
    c.emplace_back(name, "-");
  for (const auto& patch : parts_) {
    const auto part = part_name(patch);
    for (const char* kind : {"_p", "_v"}) {
      for (const char* f : {"X", "Y", "Z"}) c.emplace_back(part + "." + f + kind, "N");
      for (const char* f : {"K", "M", "N"}) c.emplace_back(part + "." + f + kind, "N m");
    }
  }
  return c;
}

std::vector<std::pair<std::string, double>> CfdPlant::wall_clock() const {
  return {{"fins", clock_[0]},     {"coupling", clock_[1]},        {"momentum", clock_[2]},
          {"pressure", clock_[3]}, {"turbulence", clock_[4]},      {"flow-other", clock_[5]},
          {"rest", clock_[6]},     {"of which overset", clock_[7]}};
}

void CfdPlant::record_signals() {
  const auto& r = report_;
  const auto& f = r.flow;
  const double phases[] = {r.seconds_fins,     r.seconds_coupling,   f.seconds_momentum,
                           f.seconds_pressure, f.seconds_turbulence, f.seconds_other};
  double sum = 0;
  for (std::size_t i = 0; i < std::size(phases); ++i) {
    clock_[i] += phases[i];
    sum += phases[i];
  }
  clock_[6] += std::max(0.0, r.seconds - sum);
  clock_[7] += f.seconds_overset;
  signals_ = {r.J,
              r.inflow_speed,
              r.thrust,
              r.torque,
              static_cast<double>(f.outer_iterations),
              f.outer_residual,
              static_cast<double>(f.pressure_iterations),
              static_cast<double>(f.momentum_iterations),
              static_cast<double>(f.turbulence.k_iterations + f.turbulence.omega_iterations),
              f.max_courant,
              f.continuity_error};
  for (const auto& patch : parts_) {
    fv::PatchForce w;
    for (const auto& [name, force] : r.walls)
      if (name == patch) w = force;
    const Eigen::Vector3d* order[] = {&w.pressure, &w.pressure_moment, &w.viscous,
                                      &w.viscous_moment};
    for (const auto* v : order) signals_.insert(signals_.end(), v->data(), v->data() + 3);
  }
}

}  // namespace auvloop::engine

// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/case.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "auvloop/engine/cfd_plant.hpp"
#include "auvloop/engine/derivative_plant.hpp"
#include "auvloop/geometry/file_io.hpp"
#include "auvloop/mesher/mesh_settings.hpp"

namespace auvloop::engine {
namespace {
using input::Range;
using input::Table;
constexpr double kDeg = std::numbers::pi / 180;

PidGains read_gains(Table& t) {
  return {t.number("kp", Range::non_negative(), "rad/rad"),
          t.number("ki", Range::non_negative(), "1/s"), t.number("kd", Range::non_negative(), "s")};
}

ManoeuvreSpec read_manoeuvre(Table root, Table m, const ActuatorLimits& rudder) {
  const std::string type =
      m.choice("type", {"heading-step", "rudder-ramp", "turning-circle", "zigzag"});
  if (type == "heading-step") {
    HeadingStepSpec h;
    h.target_heading = m.angle("target_heading", Range::closed(-180, 180));
    auto c = root.table("controller");
    h.gains = read_gains(c);
    h.options.anti_windup = c.boolean_or("anti_windup", false);
    h.options.derivative_filter = c.number_or("derivative_filter", 0.0, Range::non_negative(), "s");
    h.options.output_limit = rudder.max;
    c.finish();
    m.finish();
    return h;
  }
  if (root.has("controller")) {
    root.fail("controller",
              fmt::format("a \"{}\" manoeuvre is open loop: remove [controller]", type));
    root.ignore("controller");
  }
  if (type == "rudder-ramp") {
    RudderRampSpec r;
    r.surface = m.choice_or("surface", "rudder", {"rudder", "stern-plane"}) == "rudder"
                    ? RudderRamp::Surface::rudder
                    : RudderRamp::Surface::stern_plane;
    r.angle = m.angle("angle", Range::closed(-90, 90));
    r.rate = m.angle("rate", Range{0, 1000, true, false});
    r.start = m.number_or("start", 0.0, Range::non_negative(), "s");
    r.report_time = m.number_or("report_time", 5.0, Range::positive(), "s");
    m.finish();
    return r;
  }
  if (type == "turning-circle") {
    TurningCircleSpec tc;
    tc.rudder = m.angle_or("rudder", rudder.max / kDeg, Range::closed(-90, 90));
    tc.rate = m.angle_or("rate", rudder.max_rate / kDeg, Range{0, 1000, true, false});
    m.finish();
    return tc;
  }
  ZigZagSpec z;
  z.rudder = m.angle("rudder", Range{0, 90, true, false});
  z.switch_heading = m.angle("switch_heading", Range{0, 90, true, false});
  m.finish();
  return z;
}

ActuatorLimits read_angle_actuator(std::optional<Table> t, double tau, double limit_deg,
                                   double rate_deg) {
  ActuatorLimits a;
  if (t) {
    tau = t->number_or("time_constant", tau, Range::non_negative(), "s");
    limit_deg = t->number_or("limit", limit_deg, Range{0, 90, true, false}, "deg");
    rate_deg = t->number_or("rate_limit", rate_deg, Range{0, 1e4, true, false}, "deg/s");
    t->finish();
  }
  a.time_constant = tau;
  a.max = limit_deg * kDeg;
  a.min = -a.max;
  a.max_rate = rate_deg * kDeg;
  return a;
}

void read_actuators(Table root, CaseSpec& c) {
  auto act = root.optional_table("actuators");
  // Defaults where the paper is silent (docs/case-file.md): a fast servo (0.1 s) limited to
  // 30 deg, the paper's large-angle range, at 30 deg/s; a propeller lag of 0.5 s.
  c.rudder = read_angle_actuator(act ? act->optional_table("rudder") : std::nullopt, 0.1, 30, 30);
  c.stern_plane =
      read_angle_actuator(act ? act->optional_table("stern_plane") : std::nullopt, 0.1, 30, 30);
  c.propeller.time_constant = 0.5;
  c.propeller.min = 0;
  c.propeller.max = 3000;
  if (act) {
    if (auto p = act->optional_table("propeller")) {
      c.propeller.time_constant = p->number_or("time_constant", 0.5, Range::non_negative(), "s");
      c.propeller.max = p->number_or("max_rpm", 3000, Range::positive(), "rev/min");
      p->finish();
    }
    act->finish();
  }
}

void read_body(Table root, CaseSpec& c, const VehicleResolver& resolve_vehicle) {
  c.name = root.text("name");
  c.description = root.text_or("description", "");
  c.vehicle_spec = root.text_or("vehicle", "preset:remus100");
  c.plant = plant_kind_from_string(
      root.choice_or("plant", "derivative", {"derivative", "linearized", "cfd"}));
  c.horizontal_linearization =
      root.choice_or("linearization", "horizontal", {"horizontal", "full"}) == "horizontal";
  c.buoyancy = root.choice_or("buoyancy", "neutral", {"neutral", "vehicle"}) == "neutral"
                   ? Buoyancy::neutral
                   : Buoyancy::vehicle;
  try {
    c.vehicle = resolve_vehicle(c.vehicle_spec);
  } catch (const input::InputError& e) {
    root.fail("vehicle", fmt::format("the vehicle cannot be used:\n{}", e.what()));
  } catch (const std::invalid_argument& e) {
    root.fail("vehicle", e.what());
  }
  auto time = root.table("time");
  c.dt = time.number("dt", Range{0, 1, true, false}, "s");
  c.duration = time.number("duration", Range{0, 86400, true, false}, "s");
  time.finish();
  if (c.duration < c.dt) time.fail("duration", "must be at least one time step (dt)");
}

// The root [mesh] table of a CFD case: the grids' settings on top of [cfd] mesh's preset.
void read_mesh(Table root, CaseSpec& c) {
  auto t = root.optional_table("mesh");
  if (!t) return;
  if (c.plant != PlantKind::cfd) {
    root.fail("mesh",
              fmt::format("[mesh] applies to plant = \"cfd\", not \"{}\"", to_string(c.plant)));
    root.ignore("mesh");
    return;
  }
  if (t->has("preset")) {
    t->fail("preset", "a CFD case names its preset in [cfd] mesh");
    t->ignore("preset");
  }
  if (t->has("fin_deflections")) {
    t->fail("fin_deflections", "the CFD plant turns the fins itself: leave them out");
    t->ignore("fin_deflections");
  }
  c.cfd.mesh_settings = mesher::read_mesh_settings(*t, c.vehicle.vehicle, c.cfd.mesh);
}

void read_cfd(Table root, CaseSpec& c) {
  auto t = root.optional_table("cfd");
  if (!t) return read_mesh(root, c);
  if (c.plant != PlantKind::cfd) {
    root.fail("cfd",
              fmt::format("[cfd] applies to plant = \"cfd\", not \"{}\"", to_string(c.plant)));
    root.ignore("cfd");
    return;
  }
  auto& f = c.cfd;
  f.mesh = t->choice_or("mesh", "coarse", {"coarse", "medium", "fine"});
  f.outer_iterations = static_cast<int>(t->integer_or("outer_iterations", 5, 1, 50));
  f.sst = t->choice_or("turbulence", "sst", {"sst", "laminar"}) == "sst";
  f.horizontal = t->choice_or("dof", "6dof", {"6dof", "horizontal"}) == "horizontal";
  f.spin_up = t->number_or("spin_up", 2.0, Range::closed(0, 600), "s");
  f.relax_u = t->number_or("relax_u", 0.7, Range::open_closed(0, 1), "");
  f.relax_p = t->number_or("relax_p", 0.3, Range::open_closed(0, 1), "");
  f.pressure_correctors = static_cast<int>(t->integer_or("pressure_correctors", 2, 1, 10));
  f.turbulence_final_only = t->boolean_or("turbulence_final_only", true);
  f.tolerance = t->number_or("tolerance", 1e-6, Range::closed(1e-14, 1e-3), "");
  f.intermediate_tolerance =
      t->number_or("intermediate_tolerance", 1e-4, Range::closed(0, 0.1), "");
  f.max_flow_speed = t->number_or("max_flow_speed", 20, Range::non_negative(), "m/s");
  f.fields_at = t->optional_numbers("fields_at", 1, 100, Range::open_closed(0, c.duration), "s")
                    .value_or(std::vector<double>{});
  f.disk_mean_inflow = t->choice_or("propeller_inflow", "plane", {"plane", "disk"}) == "disk";
  f.threads = static_cast<int>(t->integer_or("threads", 0, 0, 256));
  t->finish();
  read_mesh(root, c);
}

// Defaults tuned on the derivative plant at 1500 rpm (docs/case-file.md, "Speed control").
constexpr double kSpeedKp = 2000.0;  // rev/min per m/s
constexpr double kSpeedKi = 500.0;   // rev/min per m

void read_speed_control(Table root, CaseSpec& c) {
  auto t = root.optional_table("speed_control");
  if (!t) return;
  SpeedControlSettings s;
  s.speed = t->number_or("speed", c.initial_speed, Range::closed(0, 20), "m/s");
  s.kp = t->number_or("kp", kSpeedKp, Range::non_negative(), "rev/min per m/s");
  s.ki = t->number_or("ki", kSpeedKi, Range::non_negative(), "rev/min per m");
  s.feed_forward = c.rpm;
  s.max_rpm = c.propeller.max;
  t->finish();
  c.speed_control = s;
}

void read_initial(Table root, CaseSpec& c) {
  auto init = root.optional_table("initial");
  c.rpm = init ? init->number_or("rpm", 1500, Range::non_negative(), "rev/min") : 1500;
  const bool have_model = c.vehicle.hydrodynamics.reference_rpm > 0;
  const double trim = have_model
                          ? PresteroModel(c.vehicle.vehicle, c.vehicle.hydrodynamics, c.buoyancy)
                                .equilibrium_speed(c.rpm)
                          : 0.0;
  c.initial_speed = init ? init->number_or("speed", trim, Range::closed(0, 20), "m/s") : trim;
  c.initial_heading = init ? init->angle_or("heading", 0, Range::closed(-180, 180)) : 0;
  if (init) init->finish();
}

}  // namespace

std::string CaseSpec::manoeuvre_type() const {
  static constexpr const char* names[] = {"heading-step", "rudder-ramp", "turning-circle",
                                          "zigzag"};
  return names[manoeuvre.index()];
}

VehicleResolver file_vehicle_resolver(const std::filesystem::path& base_dir) {
  return [base_dir](const std::string& spec) {
    const bool preset = spec.starts_with("preset:");
    return load_vehicle_model(
        preset || std::filesystem::path(spec).is_absolute() ? spec : (base_dir / spec).string());
  };
}

CaseSpec parse_case(std::string_view text, const std::string& source_name,
                    const std::filesystem::path& base_dir) {
  return parse_case(text, source_name, file_vehicle_resolver(base_dir));
}

CaseSpec parse_case(std::string_view text, const std::string& source_name,
                    const VehicleResolver& resolve_vehicle) {
  auto doc = input::Document::parse(text, source_name);
  auto root = doc.root();
  CaseSpec c;
  read_body(root, c, resolve_vehicle);
  read_cfd(root, c);
  read_initial(root, c);
  read_actuators(root, c);
  read_speed_control(root, c);
  c.manoeuvre = read_manoeuvre(root, root.table("manoeuvre"), c.rudder);
  auto sensors = root.optional_table("sensors");
  c.ideal_sensors =
      sensors && sensors->choice_or("type", "virtual-ins", {"virtual-ins", "ideal"}) == "ideal";
  if (sensors) sensors->finish();
  if (auto idx = root.optional_table("indices")) {
    const auto rise = idx->optional_numbers("rise", 2, 2, Range{0, 100, true, true}, "%");
    if (rise) {
      c.indices.rise_low = (*rise)[0] / 100;
      c.indices.rise_high = (*rise)[1] / 100;
      if (c.indices.rise_low >= c.indices.rise_high)
        idx->fail("rise", "the first level must be below the second");
    }
    c.indices.settling_band =
        idx->number_or("settling_band", 2, Range{0, 50, true, false}, "%") / 100;
    idx->finish();
  }
  root.finish();
  doc.check();
  return c;
}

CaseSpec load_case(const std::filesystem::path& path) {
  return parse_case(input::read_file(path), path.string(), path.parent_path());
}

nlohmann::json canonical_json(const CaseSpec& c) {
  using nlohmann::json;
  const auto deg = [](double rad) { return rad / kDeg; };
  const auto actuator = [&](const ActuatorLimits& a, bool angle) {
    return json{{"time_constant_s", a.time_constant},
                {"min", angle ? deg(a.min) : a.min},
                {"max", angle ? deg(a.max) : a.max},
                {"max_rate", angle ? deg(a.max_rate) : a.max_rate}};
  };
  json coefficients;
  for (const auto& f : PresteroCoefficients::fields()) {
    coefficients[std::string(f.name)] = c.vehicle.hydrodynamics.*f.member;
  }
  const auto& h = c.vehicle.hydrodynamics;
  const auto& mass = c.vehicle.vehicle.mass;
  json j{
      {"name", c.name},
      {"plant", to_string(c.plant)},
      {"buoyancy", c.buoyancy == Buoyancy::neutral ? "neutral" : "vehicle"},
      {"dt_s", c.dt},
      {"duration_s", c.duration},
      {"initial",
       {{"speed_m_s", c.initial_speed}, {"heading_deg", deg(c.initial_heading)}, {"rpm", c.rpm}}},
      {"actuators",
       {{"rudder_deg", actuator(c.rudder, true)},
        {"stern_plane_deg", actuator(c.stern_plane, true)},
        {"propeller_rpm", actuator(c.propeller, false)}}},
      {"sensors", c.ideal_sensors ? "ideal" : "virtual-ins"},
      {"indices",
       {{"rise_low", c.indices.rise_low},
        {"rise_high", c.indices.rise_high},
        {"settling_band", c.indices.settling_band}}},
      {"vehicle",
       {{"spec", c.vehicle_spec},
        {"mass_kg", mass.mass},
        {"buoyancy_N", mass.buoyancy},
        {"gravity", mass.gravity},
        {"cg_m", {mass.cg_from_cb.x(), mass.cg_from_cb.y(), mass.cg_from_cb.z()}},
        {"inertia_kg_m2",
         {{mass.inertia(0, 0), mass.inertia(0, 1), mass.inertia(0, 2)},
          {mass.inertia(1, 0), mass.inertia(1, 1), mass.inertia(1, 2)},
          {mass.inertia(2, 0), mass.inertia(2, 1), mass.inertia(2, 2)}}},
        {"hydrodynamics",
         {{"coefficients", coefficients},
          {"fin_pair_factor", h.fin_pair_factor},
          {"X_prop", h.X_prop},
          {"K_prop", h.K_prop},
          {"reference_rpm", h.reference_rpm}}}}}};
  if (c.speed_control) {  // only when present: the keys of cases without it are unchanged
    const auto& sc = *c.speed_control;
    j["speed_control"] = {{"speed_m_s", sc.speed},
                          {"kp_rpm_per_m_s", sc.kp},
                          {"ki_rpm_per_m", sc.ki},
                          {"feed_forward_rpm", sc.feed_forward},
                          {"max_rpm", sc.max_rpm}};
  }
  if (c.plant == PlantKind::cfd) {
    const auto& w = c.vehicle.vehicle.propeller.open_water;
    j["cfd"] = {{"mesh", c.cfd.mesh},
                {"outer_iterations", c.cfd.outer_iterations},
                {"turbulence", c.cfd.sst ? "sst" : "laminar"},
                {"dof", c.cfd.horizontal ? "horizontal" : "6dof"},
                {"spin_up_s", c.cfd.spin_up},
                {"relax_u", c.cfd.relax_u},
                {"relax_p", c.cfd.relax_p},
                {"pressure_correctors", c.cfd.pressure_correctors},
                {"turbulence_final_only", c.cfd.turbulence_final_only},
                {"tolerance", c.cfd.tolerance},
                {"intermediate_tolerance", c.cfd.intermediate_tolerance},
                {"max_flow_speed_m_s", c.cfd.max_flow_speed},
                {"mesh_settings",
                 c.cfd.mesh_settings
                     ? nlohmann::json::parse(mesher::mesh_settings_json(*c.cfd.mesh_settings))
                     : nlohmann::json()},
                {"fields_at_s", c.cfd.fields_at}};
    if (c.cfd.disk_mean_inflow) j["cfd"]["propeller_inflow"] = "disk";  // the default's keys kept
    // The grids' revision: mesh_settings_json carries it when a [mesh] table is given (one place).
    if (!c.cfd.mesh_settings) j["cfd"]["mesh_revision"] = mesher::mesh_preset_revision();
    // The flow sees the vehicle's shape, not only its name: a vehicle file edited in place
    // must not find the old file's results or straight run.
    const auto& v = c.vehicle.vehicle;
    const auto& hull = v.hull;
    const auto& fins = v.fin_set;
    const auto& prop = v.propeller;
    json placements = json::array();
    for (const auto& f : fins.fins)
      placements.push_back({{"name", f.name}, {"roll_deg", deg(f.roll)}});
    j["vehicle"]["geometry"] = {{"hull",
                                 {{"a", hull.a},
                                  {"a_offset", hull.a_offset},
                                  {"b", hull.b},
                                  {"c", hull.c},
                                  {"c_offset", hull.c_offset},
                                  {"d", hull.d},
                                  {"n", hull.n},
                                  {"theta_deg", deg(hull.theta)}}},
                                {"cb_station_m", mass.cb_station},
                                {"fins",
                                 {{"placements", placements},
                                  {"section", fins.section.designation()},
                                  {"sharp_trailing_edge", fins.section.sharp_trailing_edge},
                                  {"root_chord", fins.root_chord},
                                  {"tip_chord", fins.tip_chord},
                                  {"span", fins.span},
                                  {"sweep_deg", deg(fins.sweep)},
                                  {"root_le_station", fins.root_le_station},
                                  {"tip_radius", fins.tip_radius},
                                  {"post_station", fins.post_station},
                                  {"root_gap", fins.root_gap},
                                  {"max_deflection_deg", deg(fins.max_deflection)}}}};
    j["vehicle"]["water_density_kg_m3"] = mass.water_density;
    j["vehicle"]["propeller"] = {{"diameter_m", prop.diameter},
                                 {"hub_diameter_m", prop.hub_diameter},
                                 {"station_m", prop.station},
                                 {"disk_thickness_m", prop.disk_thickness},
                                 {"open_water", {{"J", w.J}, {"KT", w.KT}, {"KQ", w.KQ}}}};
  }
  std::visit(
      [&](const auto& m) {
        using T = std::decay_t<decltype(m)>;
        json& out = j["manoeuvre"];
        out["type"] = c.manoeuvre_type();
        if constexpr (std::is_same_v<T, HeadingStepSpec>) {
          out["target_heading_deg"] = deg(m.target_heading);
          out["controller"] = {{"kp", m.gains.kp},
                               {"ki", m.gains.ki},
                               {"kd", m.gains.kd},
                               {"anti_windup", m.options.anti_windup},
                               {"derivative_filter_s", m.options.derivative_filter}};
        } else if constexpr (std::is_same_v<T, RudderRampSpec>) {
          out["surface"] = m.surface == RudderRamp::Surface::rudder ? "rudder" : "stern-plane";
          out["angle_deg"] = deg(m.angle);
          out["rate_deg_s"] = deg(m.rate);
          out["start_s"] = m.start;
          out["report_time_s"] = m.report_time;
        } else if constexpr (std::is_same_v<T, TurningCircleSpec>) {
          out["rudder_deg"] = deg(m.rudder);
          out["rate_deg_s"] = deg(m.rate);
        } else {
          out["rudder_deg"] = deg(m.rudder);
          out["switch_heading_deg"] = deg(m.switch_heading);
        }
      },
      c.manoeuvre);
  return j;
}

nlohmann::json straight_run_json(const CaseSpec& c) {
  auto all = canonical_json(c);
  nlohmann::json j{{"what", "the straight run of a CFD case before t = 0"},
                   {"plant", all["plant"]},
                   {"buoyancy", all["buoyancy"]},
                   {"dt_s", all["dt_s"]},
                   {"speed_m_s", all["initial"]["speed_m_s"]},
                   {"rpm", all["initial"]["rpm"]},
                   {"vehicle", all["vehicle"]}};
  if (all.contains("cfd")) {
    j["cfd"] = all["cfd"];
    j["cfd"].erase("dof");  // every degree of freedom is held in the straight run
  }
  return j;
}

namespace {
std::unique_ptr<Manoeuvre> make_manoeuvre(const CaseSpec& c) {
  auto manoeuvre = std::visit(
      [&](const auto& m) -> std::unique_ptr<Manoeuvre> {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, HeadingStepSpec>) {
          return std::make_unique<HeadingStep>(m.target_heading, m.gains, m.options, c.rpm);
        } else if constexpr (std::is_same_v<T, RudderRampSpec>) {
          return std::make_unique<RudderRamp>(m.surface, m.angle, m.rate, m.start, c.rpm);
        } else if constexpr (std::is_same_v<T, TurningCircleSpec>) {
          return std::make_unique<RudderRamp>(RudderRamp::Surface::rudder, m.rudder, m.rate, 0.0,
                                              c.rpm);
        } else {
          return std::make_unique<ZigZag>(m.rudder, m.switch_heading, c.initial_heading, c.rpm);
        }
      },
      c.manoeuvre);
  if (!c.speed_control) return manoeuvre;
  return std::make_unique<SpeedControl>(std::move(manoeuvre), *c.speed_control);
}
}  // namespace

const char* to_string(PlantKind k) {
  switch (k) {
    case PlantKind::derivative:
      return "derivative";
    case PlantKind::linearized:
      return "linearized";
    case PlantKind::cfd:
      return "cfd";
  }
  return "?";
}

PlantKind plant_kind_from_string(const std::string& s) {
  for (auto k : {PlantKind::derivative, PlantKind::linearized, PlantKind::cfd})
    if (s == to_string(k)) return k;
  throw std::invalid_argument("unknown plant '" + s + "' (derivative, linearized, cfd)");
}

CaseRun run_case(const CaseSpec& c, const std::function<void(double t)>& progress) {
  CaseRunOptions o;
  o.progress = progress;
  return run_case(c, o);
}

namespace {
constexpr std::string_view kStraightRunTag = "auvloop straight run";

// The store of straight runs keeps the kStraightRunsKept most recently used (a load touches its
// file); older ones go when a new one is stored. Errors are left: pruning is housekeeping.
constexpr std::size_t kStraightRunsKept = 16;  // about 23 MB each on coarse, 100 MB on medium

void prune_straight_runs(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() != ".flow" || !e.is_regular_file(ec)) continue;
    files.emplace_back(e.last_write_time(ec), e.path());
  }
  if (files.size() <= kStraightRunsKept) return;
  std::sort(files.begin(), files.end(), std::greater<>());  // newest first
  for (std::size_t i = kStraightRunsKept; i < files.size(); ++i) fs::remove(files[i].second, ec);
}
}  // namespace

CfdPlantSettings cfd_plant_settings(const CaseSpec& c) {
  CfdPlantSettings s;
  s.mesh = c.cfd.mesh;
  s.outer_iterations = c.cfd.outer_iterations;
  s.sst = c.cfd.sst;
  if (c.cfd.horizontal) s.free = DfbiBody::horizontal;
  s.relax_u = c.cfd.relax_u;
  s.relax_p = c.cfd.relax_p;
  s.pressure_correctors = c.cfd.pressure_correctors;
  s.tolerance = c.cfd.tolerance;
  s.turbulence_final_only = c.cfd.turbulence_final_only;
  s.intermediate_tolerance = c.cfd.intermediate_tolerance;
  s.max_flow_speed = c.cfd.max_flow_speed;
  s.mesh_settings = c.cfd.mesh_settings;
  if (c.cfd.disk_mean_inflow) s.inflow_offset = 0;  // fv::DiskForce step 4: the disk cells' mean
  s.reference_speed = std::max(c.initial_speed, 0.1);
  s.added_mass = prestero_added_mass(c.vehicle.hydrodynamics);
  s.neutral_buoyancy = c.buoyancy == Buoyancy::neutral;
  return s;
}

CaseRun run_case(const CaseSpec& c, const CaseRunOptions& options) {
  // The CFD plant's threads: every parallel loop of the mesher and the solver runs on oneTBB's
  // pool, which this caps for the run's life (0: no cap, every core the process may use).
  std::optional<tbb::global_control> threads;
  if (c.plant == PlantKind::cfd && c.cfd.threads > 0)
    threads.emplace(tbb::global_control::max_allowed_parallelism,
                    static_cast<std::size_t>(c.cfd.threads));
  const auto& progress = options.progress;
  const bool resuming =
      options.resume && !options.checkpoint.empty() && std::filesystem::exists(options.checkpoint);
  const PresteroModel model(c.vehicle.vehicle, c.vehicle.hydrodynamics, c.buoyancy);
  std::unique_ptr<Plant> plant;
  const CfdPlant* cfd_plant = nullptr;  // the CFD plant's output (after_step)
  CaseRun run;
  BodyState initial;
  initial.nu[0] = c.initial_speed;
  initial.attitude = quaternion_from_euler({0, 0, c.initial_heading});
  if (c.plant == PlantKind::derivative) {
    plant = std::make_unique<DerivativePlant>(model);
  } else if (c.plant == PlantKind::cfd) {
    auto cfd = std::make_unique<CfdPlant>(c.vehicle.vehicle, cfd_plant_settings(c));
    // The straight run the manoeuvre starts from (progress below zero: before t = 0): a resumed
    // run's flow is in its checkpoint; a stored one is loaded; else it is computed (and stored).
    std::optional<PlantFailure> failure;
    const auto& file = options.straight_run;
    if (resuming) {
      run.straight_run = "in the checkpoint";
    } else if (!file.empty() && std::filesystem::exists(file)) {
      try {
        StateReader in(read_file_text(file), file.string());
        in.expect_tag(kStraightRunTag);
        cfd->load(in);
        in.expect_end();
        run.straight_run = "loaded from " + file.string();
        std::error_code ec;  // in use: the last to be pruned
        std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ec);
      } catch (const std::runtime_error& e) {
        run.straight_run_warning =
            fmt::format("the stored straight run was not used: {}", e.what());
      }
    }
    if (run.straight_run.empty()) {
      failure = cfd->spin_up(initial, c.rpm, c.cfd.spin_up, c.dt, [&](double t) {
        if (progress) progress(t - c.cfd.spin_up);
      });
      run.straight_run = "computed";
      if (!failure && !file.empty()) {
        try {
          StateWriter out;
          out.tag(kStraightRunTag);
          cfd->save(out);
          if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
          write_file_atomically(file, out.bytes());
          run.straight_run = "computed and stored in " + file.string();
          if (file.has_parent_path()) prune_straight_runs(file.parent_path());
        } catch (const std::exception& e) {
          run.straight_run_warning = fmt::format("the straight run was not stored: {}", e.what());
        }
      }
    }
    if (failure) {
      run.plant_name = cfd->name();
      run.loop.failure =
          fmt::format("the cfd plant's straight run before t = 0 diverged: {}", failure->reason);
      return run;
    }
    cfd_plant = cfd.get();
    plant = std::move(cfd);
  } else {
    auto lin = linearize_straight_running(model, c.rpm, c.horizontal_linearization);
    run.eigenvalues = lin.eigenvalues();
    plant = std::make_unique<LinearizedPlant>(std::move(lin));
  }
  run.plant_name = plant->name();
  IdealSensors ideal;
  VirtualIns ins;
  Sensors& sensors = c.ideal_sensors ? static_cast<Sensors&>(ideal) : static_cast<Sensors&>(ins);
  auto manoeuvre = make_manoeuvre(c);
  Actuators actuators{FirstOrderActuator(c.rudder, 0.0), FirstOrderActuator(c.stern_plane, 0.0),
                      FirstOrderActuator(c.propeller, c.rpm)};
  const double every = options.checkpoint_every > 0 ? options.checkpoint_every
                       : c.plant == PlantKind::cfd  ? 1.0
                                                    : 0.0;
  // The steps whose flow is kept: the nearest to each of [cfd] fields_at.
  std::vector<long> field_steps;
  if (cfd_plant != nullptr && !options.fields.empty())
    for (double t : c.cfd.fields_at) field_steps.push_back(std::max(1L, std::lround(t / c.dt)));
  const auto keep_fields = [&](long step, double t) {
    if (std::find(field_steps.begin(), field_steps.end(), step) == field_steps.end()) return;
    namespace fs = std::filesystem;
    try {  // a full disk or a bad directory costs the pictures, never the run
      fs::create_directories(options.fields);
      cfd_plant->write_fields(options.fields / fmt::format("flow_{:06d}.vtu", step));
      write_file_atomically(options.fields / fmt::format("snapshot_{:06d}.json", step),
                            flow_snapshot_json(cfd_plant->snapshot(t)).dump() + "\n");
    } catch (const std::exception& e) {
      run.fields_warning = fmt::format("the flow at t = {:g} s was not kept: {}", t, e.what());
    }
  };
  run.loop =
      run_closed_loop(*plant, sensors, *manoeuvre, actuators, initial,
                      {.dt = c.dt,
                       .duration = c.duration,
                       .progress = progress,
                       .progress_every = c.plant == PlantKind::cfd ? 1 : 100,
                       .after_step = keep_fields,
                       .checkpoint = options.checkpoint,
                       .checkpoint_every = every > 0 ? std::max(1L, std::lround(every / c.dt)) : 0,
                       .checkpoint_key = options.checkpoint_key,
                       .resume = options.resume});
  run.wall_clock = plant->wall_clock();
  return run;
}

nlohmann::json flow_snapshot_json(const FlowSnapshot& s) {
  nlohmann::json speed = nlohmann::json::array();
  for (double v : s.speed) speed.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
  nlohmann::json faces = nlohmann::json::array();
  for (const auto& f : s.faces) faces.push_back({f.x, f.height, f.side, f.p});
  return {{"time_s", s.time},
          {"plane",
           {{"x0_m", s.x0},
            {"y0_m", s.y0},
            {"h_m", s.h},
            {"nx", s.nx},
            {"ny", s.ny},
            {"speed_m_per_s", speed}}},
          {"fin",
           {{"name", s.fin},
            {"deflection_deg", s.deflection * 180 / std::numbers::pi},
            {"faces_x_height_side_p", faces}}}};
}

}  // namespace auvloop::engine

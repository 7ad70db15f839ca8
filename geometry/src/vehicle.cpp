// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/vehicle.hpp"

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "auvloop/geometry/fin.hpp"
#include "auvloop/geometry/myring.hpp"

namespace auvloop::embedded {
extern const std::string_view remus100_toml;
}

namespace auvloop::geometry {
namespace {

using input::Range;
using input::Table;

constexpr double kDeg = std::numbers::pi / 180.0;

MyringParameters read_hull(Table t) {
  MyringParameters h;
  h.a = t.number("a", Range::positive(), "m");
  h.a_offset = t.number("a_offset", Range::non_negative(), "m");
  h.b = t.number("b", Range::non_negative(), "m");
  h.c = t.number("c", Range::positive(), "m");
  h.c_offset = t.number("c_offset", Range::non_negative(), "m");
  h.d = t.number("d", Range::positive(), "m");
  h.n = t.number("n", Range::open_closed(0, 10), "");
  h.theta = t.angle("theta", Range::closed(0, 80));
  t.finish();
  if (h.a_offset >= h.a) t.fail("a_offset", fmt::format("must be smaller than a = {:g} m", h.a));
  if (h.c_offset >= h.c) t.fail("c_offset", fmt::format("must be smaller than c = {:g} m", h.c));
  return h;
}

// The profile must stay a body: positive radius up to the tail end.
void check_profile(Table t, const MyringParameters& h) {
  if (!(h.a > h.a_offset && h.c > h.c_offset && h.d > 0 && h.n > 0)) return;
  const MyringProfile profile(h);
  for (int i = 0; i <= 200; ++i) {
    const double s = profile.tail_start() + (profile.length() - profile.tail_start()) * i / 200.0;
    if (!(profile.radius(s) > 0)) {
      t.fail("theta", fmt::format("the tail radius becomes {:.4g} m at station {:.4g} m: reduce "
                                  "theta or increase c_offset",
                                  profile.radius(s), s));
      return;
    }
  }
}

FinPlacement read_fin(Table t) {
  FinPlacement f;
  f.name = t.text("name");
  f.roll = t.angle("roll", Range{0, 360, false, true});
  t.finish();
  const bool name_ok = !f.name.empty() && f.name.find_first_not_of(
                                              "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-") == std::string::npos;
  if (!name_ok) {
    t.fail("name",
           fmt::format("\"{}\" is not a valid fin name: use letters, digits, '_' and '-'", f.name));
  }
  return f;
}

void check_fin_roots(Table t, const FinSetParameters& set, const MyringProfile& profile) {
  // The root face must lie over the hull, below the tip, and clear of the hull at every allowed
  // deflection (the overset grids resolve the gap; a fin touching the hull would need a junction).
  for (const auto& placement : set.fins) {
    const FinGeometry fin(set, placement, profile,
                          /*cb_station=*/0.0);  // stations do not depend on it
    for (double x : {0.0, 1.0}) {
      const double rho = fin.root_rho(x);
      if (!(rho < set.tip_radius * (1 - 1e-9))) {
        const bool off_hull = std::isinf(rho);
        t.fail(off_hull ? "root_le_station" : "root_gap",
               fmt::format("the root face of fin \"{}\" (hull radius plus root_gap) cannot be "
                           "placed at its {} edge: {}",
                           placement.name, x == 0 ? "leading" : "trailing",
                           off_hull ? "the edge lies beyond the hull's ends"
                                    : "the hull radius plus root_gap reaches tip_radius there"));
        return;
      }
    }
    const int steps = std::max(1, static_cast<int>(std::ceil(set.max_deflection / kDeg)));
    for (int i = -steps; i <= steps; ++i) {
      const double delta = set.max_deflection * i / steps;
      const double clearance = fin.hull_clearance(delta);
      if (clearance < 0.5 * set.root_gap) {
        t.fail("root_gap",
               fmt::format("at a deflection of {:.3g} deg the root of fin \"{}\" comes within "
                           "{:.3g} mm of the hull (root_gap {:.3g} mm): increase root_gap or "
                           "reduce max_deflection",
                           delta / kDeg, placement.name, clearance * 1e3, set.root_gap * 1e3));
        return;
      }
    }
  }
}

FinSetParameters read_fins(Table t, const MyringProfile* profile) {
  FinSetParameters s;
  const std::string section = t.text("section");
  const std::string te = t.choice_or("trailing_edge", "sharp", {"sharp", "blunt"});
  if (auto parsed = NacaSection::parse(section)) {
    s.section = *parsed;
  } else if (!section.empty()) {
    t.fail(
        "section",
        fmt::format("\"{}\" is not a NACA four-digit designation such as \"NACA 0012\"", section));
  }
  s.section.sharp_trailing_edge = te == "sharp";
  s.root_chord = t.number("root_chord", Range::positive(), "m");
  s.tip_chord = t.number("tip_chord", Range::positive(), "m");
  s.span = t.number("span", Range::positive(), "m");
  s.sweep = t.angle("sweep", Range{-80, 80, true, true});
  s.root_le_station = t.number("root_le_station", Range::positive(), "m");
  s.tip_radius = t.number("tip_radius", Range::positive(), "m");
  s.post_station = t.number("post_station", Range::positive(), "m");
  s.root_gap = t.number("root_gap", Range::positive(), "m");
  s.max_deflection = t.angle("max_deflection", Range{0, 90, false, true});
  std::set<std::string> names;
  std::set<long> rolls;
  for (auto fin_table : t.tables("fin", 1, 8)) {
    FinPlacement f = read_fin(fin_table);
    if (!names.insert(f.name).second) {
      fin_table.fail("name", fmt::format("fin name \"{}\" is used twice", f.name));
    }
    if (!rolls.insert(std::lround(f.roll / kDeg * 1000)).second) {
      fin_table.fail("roll", "two fins have the same roll angle");
    }
    s.fins.push_back(std::move(f));
  }
  t.finish();
  if (s.tip_radius <= s.span) {
    t.fail("tip_radius", fmt::format("must exceed span = {:g} m (the root station would lie at or "
                                     "below the hull axis)",
                                     s.span));
  } else if (profile != nullptr) {
    if (s.root_le_station >= profile->length()) {
      t.fail("root_le_station",
             fmt::format("lies behind the tail end ({:g} m)", profile->length()));
    } else if (t.has("fin") && !s.fins.empty() && s.root_gap > 0) {
      check_fin_roots(t, s, *profile);
    }
  }
  return s;
}

MassProperties read_mass(Table t, double hull_length) {
  MassProperties m;
  m.mass = t.number("mass", Range::positive(), "kg");
  m.buoyancy = t.number("buoyancy", Range::positive(), "N");
  m.gravity = t.number_or("gravity", 9.81, Range::open_closed(0, 30), "m/s^2");
  m.cb_station = t.number("cb_station", Range::positive(), "m");
  const auto cg = t.numbers("cg", 3, 3, Range::any(), "m");
  if (cg.size() == 3) m.cg_from_cb = Eigen::Vector3d(cg[0], cg[1], cg[2]);
  const auto inertia = t.matrix("inertia", 3, 3, Range::any(), "kg m^2");
  if (inertia.size() == 9) {
    m.inertia = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(inertia.data());
  }
  m.water_density = t.number_or("water_density", 1025.0, Range::closed(900, 1100), "kg/m^3");
  t.finish();
  if (std::isfinite(hull_length) && m.cb_station >= hull_length) {
    t.fail("cb_station", fmt::format("lies behind the tail end ({:g} m)", hull_length));
  }
  if (m.cg_from_cb.norm() > 0.5 * hull_length) {
    t.fail("cg", "is more than half a hull length from the centre of buoyancy");
  }
  if (inertia.size() == 9) {
    if ((m.inertia - m.inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * m.inertia.norm()) {
      t.fail("inertia", "the inertia tensor must be symmetric");
    } else {
      // A physical inertia tensor is positive definite and its principal moments satisfy the
      // triangle inequality I1 <= I2 + I3.
      const Eigen::Vector3d I =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m.inertia).eigenvalues();
      if (I.minCoeff() <= 0) {
        t.fail("inertia",
               fmt::format("principal moments ({:.4g}, {:.4g}, {:.4g}) kg m^2 must all be "
                           "positive",
                           I[0], I[1], I[2]));
      } else if (I[2] > I[0] + I[1] * (1 + 1e-9)) {
        t.fail("inertia", fmt::format("principal moments ({:.4g}, {:.4g}, {:.4g}) kg m^2 violate "
                                      "I3 <= I1 + I2: no rigid body has them",
                                      I[0], I[1], I[2]));
      }
    }
  }
  return m;
}

PropellerParameters read_propeller(Table t, double tail_start) {
  PropellerParameters p;
  p.diameter = t.number("diameter", Range::positive(), "m");
  p.hub_diameter = t.number("hub_diameter", Range::positive(), "m");
  p.station = t.number("station", Range::positive(), "m");
  p.disk_thickness = t.number("disk_thickness", Range::positive(), "m");
  if (auto w = t.optional_table("open_water")) {
    auto& c = p.open_water;
    c.source = w->text("source");
    c.J = w->numbers("J", 2, 1000, Range::non_negative(), "");
    c.KT = w->numbers("KT", 2, 1000, Range::any(), "");
    c.KQ = w->numbers("KQ", 2, 1000, Range::any(), "");
    w->finish();
    if (c.KT.size() != c.J.size() || c.KQ.size() != c.J.size())
      w->fail("J", fmt::format("J, KT and KQ must have as many entries (now {}, {}, {})",
                               c.J.size(), c.KT.size(), c.KQ.size()));
    for (std::size_t i = 1; i < c.J.size(); ++i)
      if (!(c.J[i] > c.J[i - 1])) {
        w->fail("J", fmt::format("must increase strictly: entry {} ({:g}) follows {:g}", i + 1,
                                 c.J[i], c.J[i - 1]));
        break;
      }
  }
  t.finish();
  if (p.hub_diameter >= p.diameter) {
    t.fail("hub_diameter", fmt::format("must be smaller than diameter = {:g} m", p.diameter));
  }
  if (p.disk_thickness >= p.diameter) {
    t.fail("disk_thickness", fmt::format("must be smaller than diameter = {:g} m", p.diameter));
  }
  if (std::isfinite(tail_start) && p.station <= tail_start) {
    t.fail("station",
           fmt::format("must lie on the tail or behind it (station > {:g} m)", tail_start));
  }
  return p;
}

bool hull_valid(const MyringParameters& h) {
  return h.a > h.a_offset && h.c > h.c_offset && h.d > 0 && h.n > 0 && std::isfinite(h.theta);
}

}  // namespace

Vehicle read_vehicle(Table root) {
  Vehicle v;
  v.name = root.text("name");
  v.description = root.text_or("description", "");
  Table hull_table = root.table("hull");
  v.hull = read_hull(hull_table);
  std::optional<MyringProfile> profile;
  if (hull_valid(v.hull)) {
    check_profile(hull_table, v.hull);
    profile.emplace(v.hull);
  }
  const double length = profile ? profile->length() : std::numeric_limits<double>::quiet_NaN();
  const double tail_start =
      profile ? profile->tail_start() : std::numeric_limits<double>::quiet_NaN();
  v.mass = read_mass(root.table("mass"), length);
  if (auto fins = root.optional_table("fins")) {
    v.fin_set = read_fins(*fins, profile ? &*profile : nullptr);
  }
  v.propeller = read_propeller(root.table("propeller"), tail_start);
  // The hydrodynamic model of the same file is read by the engine (engine/vehicle_model.hpp).
  root.ignore("hydrodynamics");
  return v;
}

Vehicle parse_vehicle(std::string_view toml_text, const std::string& source_name) {
  auto doc = input::Document::parse(toml_text, source_name);
  auto root = doc.root();
  Vehicle v = read_vehicle(root);
  root.finish();
  doc.check();
  v.source = source_name;
  return v;
}

Vehicle load_vehicle(const std::filesystem::path& path) {
  return parse_vehicle(input::read_file(path), path.string());
}

std::vector<std::string> preset_names() {
  return {"remus100"};
}

std::string_view preset_text(std::string_view name) {
  if (name == "remus100") return embedded::remus100_toml;
  throw std::invalid_argument(
      fmt::format("unknown vehicle preset \"{}\" (available: remus100)", name));
}

Vehicle preset_vehicle(std::string_view name) {
  Vehicle v = parse_vehicle(preset_text(name), fmt::format("preset:{}", name));
  return v;
}

Vehicle resolve_vehicle(std::string_view spec) {
  if (spec.empty()) return preset_vehicle("remus100");
  if (spec.starts_with("preset:")) return preset_vehicle(spec.substr(7));
  return load_vehicle(std::filesystem::path(spec));
}

double fin_deflection(const FinPlacement& fin, double delta_r, double delta_s) {
  // A small rotation delta about the outward post axis e_s = (0, sin roll, -cos roll) moves the
  // trailing edge (along e_c = -x from the post) by delta * e_s x e_c = delta * (0, cos roll, sin
  // roll). delta_r > 0 must move it to port (-y), delta_s > 0 down (+z).
  auto snap = [](double g) { return std::abs(g) < 1e-12 ? 0.0 : g; };  // cos(pi/2) is 6e-17
  return snap(-std::cos(fin.roll)) * delta_r + snap(std::sin(fin.roll)) * delta_s;
}

}  // namespace auvloop::geometry

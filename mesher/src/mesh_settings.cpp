// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/mesh_settings.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/geometry/myring.hpp"

namespace auvloop::mesher {

namespace {
constexpr double kDeg = std::numbers::pi / 180;

double skin_friction(double speed, double nu, double length) {
  return 0.026 / std::pow(speed * length / nu, 1.0 / 7);
}

double mean_chord(const geometry::Vehicle& v) {
  return 0.5 * (v.fin_set.root_chord + v.fin_set.tip_chord);
}

void apply_yplus(MeshSettings& s, const geometry::Vehicle& v) {
  const double length = geometry::MyringProfile(v.hull).length();
  s.hull.first_cell =
      flat_plate_wall_distance(s.hull_yplus, s.design_speed, s.kinematic_viscosity, length);
  s.fin.first_cell =
      flat_plate_wall_distance(s.fin_yplus, s.design_speed, s.kinematic_viscosity, mean_chord(v));
}

struct Preset {
  const char* name;
  double yplus;
  int nose, body, tail, circumferential, rim_fan;
  double rim_radius;  // m
  double hull_growth, hull_extent, fin_zone_share;
  int chordwise, span, te_fan;
  double fin_growth, fin_extent;
  double spacing, bg_growth;
};

// Counts chosen for about 50 k, 250 k and 1 M cells in all (59 k, 264 k, 1.15 M: docs/mesher.md).
// Wall counts set the wall accuracy, the growth rates the totals; the rest is set by the overset
// assembly, whose fringe cells need active donors (docs/mesher.md, "Sizing for overlap"):
//  - round the fins the hull grid is refined (40 / 48 / 56 sectors, narrowed at the fins, and
//    15 % of its rings over the fins' stations): the hull's fringe round its cells inside a fin
//    must stay clear of the fin grid's fringe at the hull (in the root gap) and at its outer
//    boundary;
//  - the fin grids reach 0.1 m from the fin and above the tip, beyond that hull fringe;
//  - the hull grid reaches past the background's fringe round its cells inside the hull (2.5
//    background cells) by more than its own two outer cells, and at the stern past the fin grids
//    (0.2 m from a 0.05 m radius clears the 0.131 m tip radius and 0.1 m above it): 0.3 m at the
//    0.07 m coarse background, 0.2 m at 0.04 m and 0.032 m.
// The coarse far field grows by 2 (1.8 cost 3.6 k more cells and changed no stencil). Coarse and
// medium grids are for wall functions (y+ 30 and 5 with the all-y+ treatment); fine resolves the
// viscous sublayer (y+ 1). Every preset rounds the rims by the same 5 mm fillet (one body for the
// grid study; a sharp rim's wedge cells made medium diverge, docs/mesher.md), with 2 / 3 / 5 cells
// on each arc (1.8 / 1.2 / 0.7 mm at the nose) and the end faces' and hull's wall cells grading
// down to them: 8 / 10 / 14 nose-face cells and 3 / 5 / 7 on the tail face keep the faces' growth
// at about 1.3 / 1.25 / 1.2, and 32 / 56 / 96 cells along the hull keep its largest cells at about
// 120 / 70 / 40 mm with a growth of 1.4 / 1.2 / 1.1 from the arcs.
constexpr Preset kPresets[] = {
    {"coarse", 30, 8, 32, 3, 40, 2, 0.005, 1.5, 0.3, 0.15, 8, 4, 3, 1.8, 0.1, 0.07, 2.0},
    {"medium", 5, 10, 56, 5, 48, 3, 0.005, 1.25, 0.2, 0.15, 10, 8, 6, 1.5, 0.1, 0.04, 1.4},
    {"fine", 1, 14, 96, 7, 56, 5, 0.005, 1.15, 0.2, 0.15, 20, 16, 10, 1.35, 0.1, 0.032, 1.15},
};
}  // namespace

double flat_plate_wall_distance(double yplus, double speed, double nu, double length) {
  const double u_tau = speed * std::sqrt(0.5 * skin_friction(speed, nu, length));
  return yplus * nu / u_tau;
}

double flat_plate_yplus(double height, double speed, double nu, double length) {
  return height / flat_plate_wall_distance(1.0, speed, nu, length);
}

int mesh_preset_revision() {
  return 2;
}

std::vector<std::string> mesh_preset_names() {
  return {"coarse", "medium", "fine"};
}

MeshSettings mesh_preset(std::string_view name, const geometry::Vehicle& v) {
  for (const Preset& p : kPresets) {
    if (name != p.name) continue;
    MeshSettings s;
    s.preset = p.name;
    s.hull_yplus = s.fin_yplus = p.yplus;
    s.hull.nose_face_cells = p.nose;
    s.hull.body_cells = p.body;
    s.hull.tail_face_cells = p.tail;
    s.hull.circumferential = p.circumferential;
    s.hull.rim_fan = p.rim_fan;
    s.hull.rim_radius = p.rim_radius;
    s.hull.growth = p.hull_growth;
    s.hull.extent = p.hull_extent;
    s.hull.fin_zone_share = p.fin_zone_share;
    s.fin.chordwise_cells = p.chordwise;
    s.fin.span_cells = p.span;
    s.fin.trailing_edge_fan = p.te_fan;
    s.fin.growth = p.fin_growth;
    s.fin.extent = s.fin.cap_height = p.fin_extent;
    const geometry::MyringProfile profile(v.hull);
    s.background.nose_x = v.mass.cb_station;
    s.background.length = profile.length();
    s.background.radius = std::max(v.fin_set.tip_radius, profile.max_radius());
    s.background.spacing = p.spacing;
    s.background.growth = p.bg_growth;
    apply_yplus(s, v);
    return s;
  }
  throw std::invalid_argument(
      fmt::format("unknown mesh preset \"{}\" (choose coarse, medium or fine)", name));
}

namespace {
void read_counts(input::Table t, std::string_view key, int& value, int min) {
  value = static_cast<int>(t.integer_or(key, value, min, 100000));
}

void read_hull(input::Table t, HullGridSpec& h, bool& first_given) {
  read_counts(t, "nose_face_cells", h.nose_face_cells, 1);
  read_counts(t, "body_cells", h.body_cells, 2);
  read_counts(t, "tail_face_cells", h.tail_face_cells, 1);
  read_counts(t, "circumferential", h.circumferential, 4);
  if (h.circumferential % 4 != 0)
    t.fail("circumferential", fmt::format("{} is not a multiple of 4", h.circumferential));
  read_counts(t, "normal_cells", h.normal_cells, 0);
  first_given = t.has("first_cell");
  h.first_cell = t.number_or("first_cell", h.first_cell, input::Range::positive(), "m");
  h.growth = t.number_or("growth", h.growth, input::Range::closed(1, 3), "");
  h.extent = t.number_or("extent", h.extent, input::Range::positive(), "m");
  h.rim_clustering =
      t.number_or("rim_clustering", h.rim_clustering, input::Range::closed(1, 2), "");
  read_counts(t, "rim_fan", h.rim_fan, 1);
  h.rim_radius = t.number_or("rim_radius", h.rim_radius, input::Range::non_negative(), "m");
  h.fin_clustering =
      t.number_or("fin_clustering", h.fin_clustering, input::Range{0, 1, false, true}, "");
  h.fin_zone_share =
      t.number_or("fin_zone_share", h.fin_zone_share, input::Range{0, 1, false, true}, "");
  h.fin_zone_ramp = t.number_or("fin_zone_ramp", h.fin_zone_ramp, input::Range::positive(), "m");
  t.finish();
}

void read_fin(input::Table t, FinGridSpec& f, bool& first_given) {
  read_counts(t, "chordwise_cells", f.chordwise_cells, 2);
  read_counts(t, "normal_cells", f.normal_cells, 0);
  read_counts(t, "gap_cells", f.gap_cells, 1);
  read_counts(t, "span_cells", f.span_cells, 1);
  read_counts(t, "cap_cells", f.cap_cells, 0);
  read_counts(t, "trailing_edge_fan", f.trailing_edge_fan, 1);
  first_given = t.has("first_cell");
  f.first_cell = t.number_or("first_cell", f.first_cell, input::Range::positive(), "m");
  f.growth = t.number_or("growth", f.growth, input::Range::closed(1, 3), "");
  f.extent = t.number_or("extent", f.extent, input::Range::positive(), "m");
  f.cap_height = t.number_or("cap_height", f.cap_height, input::Range::positive(), "m");
  f.root_depth = t.number_or("root_depth", f.root_depth, input::Range::positive(), "m");
  t.finish();
}

void read_background(input::Table t, BackgroundSpec& b) {
  b.spacing = t.number_or("spacing", b.spacing, input::Range::positive(), "m");
  b.growth = t.number_or("growth", b.growth, input::Range::closed(1, 3), "");
  b.ahead = t.number_or("ahead", b.ahead, input::Range::positive(), "L");
  b.behind = t.number_or("behind", b.behind, input::Range::positive(), "L");
  b.side = t.number_or("side", b.side, input::Range::positive(), "L");
  b.wake = t.number_or("wake", b.wake, input::Range::non_negative(), "L");
  b.margin = t.number_or("margin", b.margin, input::Range::non_negative(), "m");
  t.finish();
}
}  // namespace

MeshSettings read_mesh_settings(input::Table mesh, const geometry::Vehicle& v,
                                std::string_view preset_override) {
  const std::string from_file = mesh.choice_or("preset", "medium", {"coarse", "medium", "fine"});
  MeshSettings s = mesh_preset(preset_override.empty() ? from_file : preset_override, v);
  s.design_speed = mesh.number_or("design_speed", s.design_speed, input::Range::positive(), "m/s");
  s.kinematic_viscosity = mesh.number_or("kinematic_viscosity", s.kinematic_viscosity,
                                         input::Range::positive(), "m^2/s");
  s.hull_yplus = mesh.number_or("hull_yplus", s.hull_yplus, input::Range::positive(), "");
  s.fin_yplus = mesh.number_or("fin_yplus", s.fin_yplus, input::Range::positive(), "");
  apply_yplus(s, v);
  bool hull_first = false, fin_first = false;
  const double hull_h = s.hull.first_cell, fin_h = s.fin.first_cell;
  if (auto t = mesh.optional_table("hull")) read_hull(*t, s.hull, hull_first);
  if (auto t = mesh.optional_table("fin")) read_fin(*t, s.fin, fin_first);
  if (auto t = mesh.optional_table("background")) read_background(*t, s.background);
  if (!hull_first) s.hull.first_cell = hull_h;
  if (!fin_first) s.fin.first_cell = fin_h;
  const double limit = v.fin_set.max_deflection / kDeg;
  const auto n = v.fin_set.fins.size();
  if (auto d = mesh.optional_numbers("fin_deflections", n, n, input::Range::closed(-limit, limit),
                                     "deg")) {
    for (double deg : *d) s.fin_deflections.push_back(deg * kDeg);
  }
  mesh.finish();
  return s;
}

std::string mesh_settings_json(const MeshSettings& s) {
  const auto& h = s.hull;
  const auto& f = s.fin;
  const auto& b = s.background;
  const nlohmann::json j = {{"preset", s.preset},
                            {"revision", mesh_preset_revision()},
                            {"design_speed", s.design_speed},
                            {"kinematic_viscosity", s.kinematic_viscosity},
                            {"hull_yplus", s.hull_yplus},
                            {"fin_yplus", s.fin_yplus},
                            {"hull",
                             {{"nose_face_cells", h.nose_face_cells},
                              {"body_cells", h.body_cells},
                              {"tail_face_cells", h.tail_face_cells},
                              {"circumferential", h.circumferential},
                              {"normal_cells", h.normal_cells},
                              {"first_cell", h.first_cell},
                              {"growth", h.growth},
                              {"extent", h.extent},
                              {"rim_clustering", h.rim_clustering},
                              {"rim_fan", h.rim_fan},
                              {"rim_radius", h.rim_radius},
                              {"fins", h.fins},
                              {"fin_angle", h.fin_angle},
                              {"fin_clustering", h.fin_clustering},
                              {"fin_zone_begin", h.fin_zone_begin},
                              {"fin_zone_end", h.fin_zone_end},
                              {"fin_zone_share", h.fin_zone_share},
                              {"fin_zone_ramp", h.fin_zone_ramp}}},
                            {"fin",
                             {{"chordwise_cells", f.chordwise_cells},
                              {"normal_cells", f.normal_cells},
                              {"gap_cells", f.gap_cells},
                              {"span_cells", f.span_cells},
                              {"cap_cells", f.cap_cells},
                              {"trailing_edge_fan", f.trailing_edge_fan},
                              {"first_cell", f.first_cell},
                              {"growth", f.growth},
                              {"extent", f.extent},
                              {"cap_height", f.cap_height},
                              {"root_depth", f.root_depth}}},
                            {"background",
                             {{"nose_x", b.nose_x},
                              {"length", b.length},
                              {"radius", b.radius},
                              {"ahead", b.ahead},
                              {"behind", b.behind},
                              {"side", b.side},
                              {"spacing", b.spacing},
                              {"margin", b.margin},
                              {"wake", b.wake},
                              {"growth", b.growth}}},
                            {"fin_deflections", s.fin_deflections}};
  return j.dump();  // nlohmann::json objects keep their keys sorted
}

void check_mesh_settings(const MeshSettings& s, const geometry::Vehicle& v) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(s.design_speed > 0)) fail("mesh: design_speed must be positive");
  if (!(s.kinematic_viscosity > 0)) fail("mesh: kinematic_viscosity must be positive");
  const double r = geometry::MyringProfile(v.hull).max_radius();
  if (!(s.hull.first_cell < r)) {
    fail(
        fmt::format("mesh: hull.first_cell ({:.4g} m) must be smaller than the hull radius "
                    "({:.4g} m)",
                    s.hull.first_cell, r));
  }
  if (!s.fin_deflections.empty() && s.fin_deflections.size() != v.fin_set.fins.size()) {
    fail(fmt::format("mesh: fin_deflections has {} values; the vehicle has {} fins",
                     s.fin_deflections.size(), v.fin_set.fins.size()));
  }
  for (std::size_t i = 0; i < s.fin_deflections.size(); ++i) {
    if (std::abs(s.fin_deflections[i]) > v.fin_set.max_deflection * (1 + 1e-12)) {
      fail(fmt::format(
          "mesh: fin_deflections: {:.3g} deg for fin {} exceeds the vehicle's "
          "max_deflection of {:.3g} deg",
          s.fin_deflections[i] / kDeg, v.fin_set.fins[i].name, v.fin_set.max_deflection / kDeg));
    }
  }
}

}  // namespace auvloop::mesher

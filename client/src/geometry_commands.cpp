// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop geometry ...`: properties of a vehicle, surface export and surface checks.
#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/geometry/error.hpp"
#include "auvloop/geometry/myring.hpp"
#include "auvloop/geometry/surface.hpp"
#include "auvloop/geometry/surface_io.hpp"
#include "auvloop/geometry/vehicle.hpp"
#include "cli.hpp"

namespace auvloop::cli {
namespace {
using geometry::Vehicle;
using nlohmann::json;
constexpr double kDeg = std::numbers::pi / 180.0;

struct GeometryOptions {
  std::string vehicle;  // path or preset:NAME; empty: preset:remus100
  double edge_length = 0.005;
  bool json = false;
  std::string out;
  std::vector<double> fin_deflections_deg;
  std::optional<double> rudder_deg, stern_plane_deg;
  bool parts = false;
  double scale = 1.0;
  bool no_self_intersection_check = false;
  std::string preset = "remus100";
};

json hull_json(const geometry::HullProperties& h, const geometry::MyringParameters& p) {
  return {{"length_m", h.length},
          {"max_diameter_m", p.d},
          {"volume_m3", h.volume},
          {"wetted_area_curved_m2", h.wetted_area_curved},
          {"wetted_area_with_end_faces_m2", h.wetted_area_curved + h.end_face_area},
          {"frontal_area_m2", h.frontal_area},
          {"projected_area_m2", h.projected_area},
          {"centroid_from_nose_m", h.centroid_station},
          {"nose_face_radius_m", h.nose_radius},
          {"tail_face_radius_m", h.tail_radius}};
}

json fins_json(const Vehicle& v) {
  const auto& s = v.fin_set;
  json fins = json::array();
  for (const auto& f : s.fins) {
    fins.push_back({{"name", f.name},
                    {"roll_deg", f.roll / kDeg},
                    {"rudder_gain", geometry::fin_deflection(f, 1.0, 0.0)},
                    {"stern_plane_gain", geometry::fin_deflection(f, 0.0, 1.0)}});
  }
  const double area = 0.5 * (s.root_chord + s.tip_chord) * s.span;
  return {{"count", s.fins.size()},
          {"section", s.section.designation()},
          {"root_chord_m", s.root_chord},
          {"tip_chord_m", s.tip_chord},
          {"span_m", s.span},
          {"planform_area_each_m2", area},
          {"planform_area_total_m2", area * static_cast<double>(s.fins.size())},
          {"post_from_nose_m", s.post_station},
          {"max_deflection_deg", s.max_deflection / kDeg},
          {"fins", fins}};
}

json surface_json(const geometry::SurfaceMeasures& m) {
  return {{"vertices", m.vertices},
          {"faces", m.faces},
          {"volume_m3", m.volume},
          {"area_m2", m.area},
          {"centroid_body_m", {m.centroid.x(), m.centroid.y(), m.centroid.z()}}};
}

json info_json(const Vehicle& v, double edge_length) {
  const geometry::MyringProfile profile(v.hull);
  const auto hull = geometry::hull_properties(profile);
  const auto parts = geometry::vehicle_parts(v, {}, {edge_length});
  const auto merged = geometry::measure(geometry::merge_parts(parts));
  const auto hull_mesh = geometry::measure(parts.front().mesh);
  const double displaced = v.mass.water_density * merged.volume;
  return {{"vehicle", {{"name", v.name}, {"source", v.source}}},
          {"hull", hull_json(hull, v.hull)},
          {"fins", fins_json(v)},
          {"mass",
           {{"mass_kg", v.mass.mass},
            {"weight_N", v.mass.weight()},
            {"buoyancy_N", v.mass.buoyancy},
            {"cb_from_nose_m", v.mass.cb_station},
            {"cg_from_cb_m", {v.mass.cg_from_cb.x(), v.mass.cg_from_cb.y(), v.mass.cg_from_cb.z()}},
            {"displacement_of_surface_kg", displaced},
            {"buoyancy_of_surface_N", displaced * v.mass.gravity}}},
          {"triangulated",
           {{"edge_length_m", edge_length},
            {"hull", surface_json(hull_mesh)},
            {"hull_and_fins", surface_json(merged)},
            {"hull_volume_error_rel", hull_mesh.volume / hull.volume - 1}}}};
}

void print_info(const json& j) {
  const auto& h = j["hull"];
  const auto& f = j["fins"];
  const auto& m = j["mass"];
  const auto& t = j["triangulated"];
  auto row = [](std::string_view name, double value, std::string_view unit) {
    fmt::print("  {:<34} {:>12.6g} {}\n", name, value, unit);
  };
  fmt::print("{} ({})\n", j["vehicle"]["name"].get<std::string>(),
             j["vehicle"]["source"].get<std::string>());
  fmt::print("Hull, Myring profile (exact quadrature):\n");
  row("length", h["length_m"], "m");
  row("maximum diameter", h["max_diameter_m"], "m");
  row("volume", h["volume_m3"], "m^3");
  row("wetted area, curved surface", h["wetted_area_curved_m2"], "m^2");
  row("wetted area with end faces", h["wetted_area_with_end_faces_m2"], "m^2");
  row("frontal area", h["frontal_area_m2"], "m^2");
  row("projected (side) area", h["projected_area_m2"], "m^2");
  row("volume centroid aft of nose", h["centroid_from_nose_m"], "m");
  row("nose face radius", h["nose_face_radius_m"], "m");
  row("tail face radius", h["tail_face_radius_m"], "m");
  fmt::print("Fins: {} x {}\n", f["count"].get<std::size_t>(), f["section"].get<std::string>());
  row("planform area, each", f["planform_area_each_m2"], "m^2");
  row("planform area, all fins", f["planform_area_total_m2"], "m^2");
  for (const auto& fin : f["fins"]) {
    fmt::print("  {:<24} roll {:>5.1f} deg   deflection = {:+.3g} delta_r {:+.3g} delta_s\n",
               fin["name"].get<std::string>(), fin["roll_deg"].get<double>(),
               fin["rudder_gain"].get<double>(), fin["stern_plane_gain"].get<double>());
  }
  fmt::print("Mass:\n");
  row("mass", m["mass_kg"], "kg");
  row("weight", m["weight_N"], "N");
  row("buoyancy (file)", m["buoyancy_N"], "N");
  row("buoyancy of the surface (rho g V)", m["buoyancy_of_surface_N"], "N");
  fmt::print("Triangulated surface (edge length {} m):\n", t["edge_length_m"].get<double>());
  row("hull triangles", t["hull"]["faces"], "");
  row("hull volume, relative error", t["hull_volume_error_rel"], "");
  row("hull + fins triangles", t["hull_and_fins"]["faces"], "");
  row("hull + fins volume", t["hull_and_fins"]["volume_m3"], "m^3");
  row("hull + fins area", t["hull_and_fins"]["area_m2"], "m^2");
}

std::vector<double> requested_deflections(const Vehicle& v, const GeometryOptions& o) {
  const auto& fins = v.fin_set.fins;
  if (!o.fin_deflections_deg.empty()) {
    if (o.fin_deflections_deg.size() != fins.size()) {
      throw CLI::ValidationError(
          "--fin-deflection", fmt::format("{} values given, but the vehicle has {} fins (in file "
                                          "order: one value each, in degrees)",
                                          o.fin_deflections_deg.size(), fins.size()));
    }
    std::vector<double> out;
    for (double d : o.fin_deflections_deg) out.push_back(d * kDeg);
    return out;
  }
  std::vector<double> out;
  for (const auto& f : fins) {
    out.push_back(geometry::fin_deflection(f, o.rudder_deg.value_or(0) * kDeg,
                                           o.stern_plane_deg.value_or(0) * kDeg));
  }
  return out;
}

void run_info(const GeometryOptions& o) {
  const Vehicle v = geometry::resolve_vehicle(o.vehicle);
  const json j = info_json(v, o.edge_length);
  if (o.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    print_info(j);
  }
}

void run_export(const GeometryOptions& o) {
  const Vehicle v = geometry::resolve_vehicle(o.vehicle);
  const auto deflections = requested_deflections(v, o);
  const auto start = std::chrono::steady_clock::now();
  auto parts = geometry::vehicle_parts(v, deflections, {o.edge_length});
  if (!o.parts) {
    parts = {geometry::SurfacePart{"vehicle", geometry::merge_parts(parts)}};
  }
  geometry::write_surface(o.out, parts);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::size_t faces = 0;
  for (const auto& p : parts) faces += p.mesh.number_of_faces();
  fmt::print(
      "wrote {} ({} {}, {} triangles, body frame: origin at CB, x forward, y starboard, "
      "z down, metres) in {:.2f} s\n",
      o.out, parts.size(), parts.size() == 1 ? "closed surface" : "closed parts", faces, seconds);
}

void run_check(const GeometryOptions& o) {
  geometry::SurfaceReadOptions ro;
  ro.scale = o.scale;
  ro.check_self_intersection = !o.no_self_intersection_check;
  const auto parts = geometry::read_surface(o.out, ro);
  json j = json::array();
  for (const auto& p : parts) {
    json s = surface_json(geometry::measure(p.mesh));
    s["name"] = p.name;
    j.push_back(s);
  }
  if (o.json) {
    std::cout << json{{"file", o.out}, {"ok", true}, {"parts", j}}.dump(2) << "\n";
    return;
  }
  fmt::print("{}: {} part(s), each closed, manifold and outward-oriented\n", o.out, parts.size());
  for (const auto& s : j) {
    fmt::print("  {:<24} {:>8} triangles  volume {:.6g} m^3  area {:.6g} m^2\n",
               s["name"].get<std::string>(), s["faces"].get<std::size_t>(),
               s["volume_m3"].get<double>(), s["area_m2"].get<double>());
  }
}

void add_vehicle_options(CLI::App* cmd, GeometryOptions& o) {
  cmd->add_option("vehicle", o.vehicle,
                  "Vehicle TOML file, or preset:NAME (default: preset:remus100)");
  cmd->add_option("--edge-length", o.edge_length,
                  "Target edge length of the triangulation in metres; halving it doubles the "
                  "resolution in every direction")
      ->check(CLI::Range(1e-4, 0.1))
      ->capture_default_str();
}

}  // namespace

void register_geometry_commands(CLI::App& app) {
  auto opts = std::make_shared<GeometryOptions>();
  auto* geo =
      app.add_subcommand("geometry", "Vehicle geometry: properties, surface export, checks");
  geo->require_subcommand(1);

  auto* info =
      geo->add_subcommand("info", "Print hull, fin, mass and surface properties of a vehicle");
  add_vehicle_options(info, *opts);
  info->add_flag("--json", opts->json, "Print JSON instead of a table");
  info->footer("Example: auvloop geometry info --json > remus100.json");
  info->callback([opts] { run_info(*opts); });

  auto* exp = geo->add_subcommand(
      "export", "Write the hull and fins as a triangulated surface (format from the extension)");
  add_vehicle_options(exp, *opts);
  exp->add_option("--out,-o", opts->out,
                  "Output file: .stl (binary), .obj, .ply (binary), .gltf (+ .bin) or .glb")
      ->required();
  auto* per_fin = exp->add_option(
      "--fin-deflection", opts->fin_deflections_deg,
      "Deflection of every fin in degrees, in the order of the vehicle file, each right-handed "
      "about the fin's outward post axis");
  auto* rudder = exp->add_option(
      "--rudder", opts->rudder_deg,
      "Rudder angle delta_r in degrees (Prestero's sign: positive moves trailing edges to port)");
  auto* plane =
      exp->add_option("--stern-plane", opts->stern_plane_deg,
                      "Stern-plane angle delta_s in degrees (positive moves trailing edges down)");
  per_fin->excludes(rudder)->excludes(plane);
  exp->add_flag("--parts", opts->parts,
                "Write the hull and each fin as separate, overlapping closed parts instead of "
                "their union");
  exp->footer(
      "The default output is one closed, manifold surface: the boolean union of hull and fins.\n"
      "Coordinates are in the body frame: origin at the centre of buoyancy, x forward,\n"
      "y starboard, z down, metres.\n"
      "Example: auvloop geometry export --rudder 20 --out remus-rudder20.stl");
  exp->callback([opts] { run_export(*opts); });

  auto* chk = geo->add_subcommand(
      "check", "Read a surface file and check that it is closed, manifold and outward-oriented");
  chk->add_option("file", opts->out, "Surface file (.stl, .obj, .ply, .gltf, .glb)")->required();
  chk->add_option("--scale", opts->scale,
                  "Multiply coordinates by this factor (0.001 for a file in millimetres)")
      ->check(CLI::PositiveNumber);
  chk->add_flag("--no-self-intersection-check", opts->no_self_intersection_check,
                "Skip the self-intersection test (quadratic worst case on huge files)");
  chk->add_flag("--json", opts->json, "Print JSON");
  chk->callback([opts] { run_check(*opts); });

  auto* preset = geo->add_subcommand(
      "preset",
      "Print a built-in vehicle file, to start your own from (auvloop geometry preset > my.toml)");
  preset->add_option("name", opts->preset, "Preset name")->capture_default_str();
  preset->callback([opts] { std::cout << geometry::preset_text(opts->preset); });
}

}  // namespace auvloop::cli

// SPDX-License-Identifier: GPL-3.0-or-later
// A CFD run's flow pictures and ParaView fields in its run directory (docs/results.md), from the
// files the run kept (engine::CaseRunOptions::fields: flow_<step>.vtu, snapshot_<step>.json):
//   1. the files are copied into DIR/fields/ and DIR/fields/flow.pvd lists the .vtu files with
//      their times (from the snapshot of the same step), for ParaView to open as one series;
//   2. per snapshot, its data as gnuplot reads it (comma-separated, the plane row by row with a
//      blank line between rows, NaN in a solid; the fin's faces x, height, side, p);
//   3. per snapshot, gnuplot commands for two pictures: stern-speed-t<T>.png (the speed relative
//      to the vehicle on the plane z = 0 around the stern, the paper's Figure 20) and
//      rudder-pressure-t<T>.png (the upper fin's pressure, port and starboard faces side by
//      side on one colour scale, its Figure 21).
#include "flow_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/geometry/file_io.hpp"

namespace auvloop::results {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
std::string picture(const std::string& name, const std::string& body) {
  return fmt::format(
      "reset\nset datafile separator ','\nset termoption noenhanced\n"
      "set terminal pngcairo noenhanced size 1300,700 font 'DejaVu Sans,11'\nset output {}\n{}"
      "unset output\n",
      gnuplot_quote(name + ".png"), body);
}
}  // namespace

std::string flow_pictures(const fs::path& kept, const fs::path& dir) {
  if (kept.empty() || !fs::is_directory(kept)) return "";
  const fs::path fields = dir / "fields";
  fs::create_directories(fields);
  std::map<std::string, json> snapshots;  // by step, in order
  std::vector<std::string> vtus;
  for (const auto& entry : fs::directory_iterator(kept)) {  // 1.
    const std::string file = entry.path().filename().string();
    if (file.rfind("flow_", 0) == 0 && entry.path().extension() == ".vtu") {
      fs::copy_file(entry.path(), fields / file, fs::copy_options::overwrite_existing);
      vtus.push_back(file);
    } else if (file.rfind("snapshot_", 0) == 0 && entry.path().extension() == ".json") {
      try {
        snapshots[file.substr(9, file.size() - 9 - 5)] = json::parse(read_file_text(entry.path()));
      } catch (const json::exception& e) {
        throw std::runtime_error(fmt::format("{}: damaged: {}", entry.path().string(), e.what()));
      }
    }
  }
  std::sort(vtus.begin(), vtus.end());
  std::string pvd =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& file : vtus) {
    const std::string step = file.substr(5, file.size() - 5 - 4);
    const auto it = snapshots.find(step);
    const double t = it == snapshots.end() ? 0.0 : it->second.at("time_s").get<double>();
    pvd += fmt::format("<DataSet timestep=\"{:.12g}\" part=\"0\" file=\"{}\"/>\n", t, file);
  }
  pvd += "</Collection>\n</VTKFile>\n";
  if (!vtus.empty()) write_file_atomically(fields / "flow.pvd", pvd);

  std::string script;
  for (const auto& [step, s] : snapshots) {
    const double t = s.at("time_s").get<double>();
    const std::string tag = fmt::format("t{:.2f}", t);
    // 2. the plane
    const auto& plane = s.at("plane");
    const double x0 = plane.at("x0_m"), y0 = plane.at("y0_m"), h = plane.at("h_m");
    const int nx = plane.at("nx"), ny = plane.at("ny");
    const auto& speed = plane.at("speed_m_per_s");
    if (speed.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny))
      throw std::runtime_error(fmt::format("snapshot of step {}: {} speeds for {} x {} points",
                                           step, speed.size(), nx, ny));
    std::ostringstream out;
    double top = 0;
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const auto& v = speed[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) +
                              static_cast<std::size_t>(i)];
        out << fmt::format("{:.5f},{:.5f},", x0 + i * h, y0 + j * h)
            << (v.is_null() ? std::string("NaN") : fmt::format("{:.5g}", v.get<double>())) << "\n";
        if (!v.is_null()) top = std::max(top, v.get<double>());
      }
      out << "\n";
    }
    const std::string plane_file = fmt::format("fields/stern_{}.dat", step);
    write_file_atomically(dir / plane_file, out.str());
    // 2. the fin
    const auto& fin = s.at("fin");
    std::ostringstream faces;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& f : fin.at("faces_x_height_side_p")) {
      const double p = f.at(3);
      lo = std::min(lo, p);
      hi = std::max(hi, p);
      faces << fmt::format("{:.5f},{:.5f},{},{:.5g}\n", f.at(0).get<double>(),
                           f.at(1).get<double>(), f.at(2).get<int>(), p);
    }
    const std::string fin_file = fmt::format("fields/rudder_{}.dat", step);
    write_file_atomically(dir / fin_file, faces.str());
    // 3.
    script += picture(
        "stern-speed-" + tag,
        fmt::format(
            "set title {}\nset xlabel 'x (m, body axes, forward)'\n"
            "set ylabel 'y (m, starboard)'\nset size ratio -1\n"
            "set cblabel 'speed relative to the vehicle (m/s)'\nset cbrange [0:{:.3g}]\n"
            "set palette rgbformulae 22,13,-31\nset xrange [{}:{}]\nset yrange [{}:{}]\n"
            "plot {} using 1:2:3 with image notitle\n",
            gnuplot_quote(fmt::format("Plane z = 0 around the stern at t = {:.2f} s (white: the "
                                      "hull and fins)",
                                      t)),
            std::max(top, 1e-3), x0, x0 + (nx - 1) * h, y0, y0 + (ny - 1) * h,
            gnuplot_quote(plane_file)));
    if (fin.at("faces_x_height_side_p").empty()) continue;
    const std::string name = fin.at("name");
    const double deflection = fin.at("deflection_deg");
    const auto panel = [&](const char* title, const char* side) {
      return fmt::format(
          "set title '{}'\nplot {} using 1:($3 {} 0 ? $2 : NaN):4 with points pt 5 ps 1.6 "
          "palette notitle\n",
          title, gnuplot_quote(fin_file), side);
    };
    script += picture(
        "rudder-pressure-" + tag,
        fmt::format(
            "set multiplot layout 1,2 title {}\nset cbrange [{:.4g}:{:.4g}]\n"
            "set palette rgbformulae 33,13,10\nset cblabel 'p (Pa, gauge)'\n"
            "set xlabel 'x (m, body axes, fin at zero deflection)'\n"
            "set ylabel 'height above the axis (m)'\nset size ratio -1\n{}{}"
            "unset multiplot\n",
            gnuplot_quote(fmt::format("{} at t = {:.2f} s, deflection {:.1f} deg: pressure on "
                                      "both faces",
                                      name, t, deflection)),
            lo, std::max(hi, lo + 1e-6), panel("port face", "<"), panel("starboard face", ">")));
  }
  return script;
}

}  // namespace auvloop::results

// SPDX-License-Identifier: GPL-3.0-or-later
// Not a timing benchmark: why fringe cells took fallback donors (docs/mesher.md, Known defects).
// Assembles a preset's REMUS 100 grid system with every fin at one deflection and classifies each
// fringe cell that has no active cell of another grid containing its centre: which grid it is in,
// why it is fringe (a wall hole, a covered hole or the outer boundary within two face steps), and
// what the cells containing its centre in the other grids are (active, fringe and why, or hole
// and why). A hole is a wall hole when its centre lies inside the analytic hull or a fin other
// than its grid's own, else covered.
//   overset_fallbacks [--preset coarse|medium|fine] [--deflection DEG] [--list 1]
// --list 1 also prints every such cell: its station (m aft of the nose), height above the hull and
// offset from the nearest fin plane (m).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/overset.hpp"

using namespace auvloop;
using namespace auvloop::mesher;

namespace {
struct Options {
  std::string preset = "coarse";
  double deflection = 0;  // deg
  bool list = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--preset") {
      o.preset = value;
    } else if (key == "--deflection") {
      o.deflection = std::atof(value.c_str());
    } else if (key == "--list") {
      o.list = value == "1";
    } else {
      std::fprintf(stderr, "unknown option %s (--preset, --deflection, --list)\n", key.c_str());
      std::exit(2);
    }
  }
  return o;
}

// Face neighbours of every cell.
std::vector<std::vector<int>> adjacency(const Grid& g) {
  std::vector<std::vector<int>> nb(static_cast<std::size_t>(g.cells));
  for (int f = 0; f < g.internal_faces(); ++f) {
    const int o = g.owner[static_cast<std::size_t>(f)],
              n = g.neighbour[static_cast<std::size_t>(f)];
    nb[static_cast<std::size_t>(o)].push_back(n);
    nb[static_cast<std::size_t>(n)].push_back(o);
  }
  return nb;
}

struct Context {
  const geometry::Vehicle& vehicle;
  const GridSystem& sys;
  const OversetAssembler& assembler;
  const Assembly& assembly;
  std::vector<std::vector<std::vector<int>>> neighbours;  // per grid
  double deflection = 0;                                  // rad
  geometry::MyringProfile profile{vehicle.hull};

  [[nodiscard]] std::string kind(std::size_t g) const {
    return g == 0 ? "hull" : g + 1 == assembly.grids.size() ? "background" : "fin";
  }
  // Inside the analytic hull or a fin other than grid g's own (grid g = fin g - 1).
  [[nodiscard]] bool in_other_solid(std::size_t g, const Eigen::Vector3d& x) const {
    const double station = vehicle.mass.cb_station - x.x();
    if (g != 0 && station > 0 && station < profile.length() &&
        std::hypot(x.y(), x.z()) < profile.radius(station))
      return true;
    for (std::size_t i = 0; i < sys.fins.size(); ++i)
      if (g != i + 1 && sys.fin_geometry[i].contains(x, deflection)) return true;
    return false;
  }
  [[nodiscard]] std::string hole_cause(std::size_t g, int c) const {
    return in_other_solid(g, assembler.centre(static_cast<int>(g), c)) ? "wall" : "covered";
  }
  // Why a cell has its status: "active", "hole (wall|covered)", or "fringe (causes)" from the holes
  // within two face steps (none: the outer boundary).
  [[nodiscard]] std::string status(std::size_t g, int c) const {
    const auto& st = assembly.grids[g].status;
    const CellStatus s = st[static_cast<std::size_t>(c)];
    if (s == CellStatus::active) return "active";
    if (s == CellStatus::hole) return "hole (" + hole_cause(g, c) + ")";
    std::vector<int> ring{c}, seen{c};
    bool wall = false, covered = false;
    for (int layer = 0; layer < 2; ++layer) {
      std::vector<int> next;
      for (int q : ring)
        for (int n : neighbours[g][static_cast<std::size_t>(q)]) {
          if (std::find(seen.begin(), seen.end(), n) != seen.end()) continue;
          seen.push_back(n);
          next.push_back(n);
          if (st[static_cast<std::size_t>(n)] == CellStatus::hole)
            (hole_cause(g, n) == "wall" ? wall : covered) = true;
        }
      ring = next;
    }
    const std::string why = wall && covered ? "wall+covered"
                            : wall          ? "wall"
                            : covered       ? "covered"
                                            : "outer";
    return std::string(to_string(s)) + " (" + why + ")";
  }
  // Station, height above the hull and offset from the nearest fin plane of a body-frame point.
  void where(const Eigen::Vector3d& x, double& station, double& height, double& offset) const {
    station = vehicle.mass.cb_station - x.x();
    const double rho = std::hypot(x.y(), x.z()), roll = std::atan2(x.y(), -x.z());
    double nearest = std::numbers::pi;
    for (const auto& fin : vehicle.fin_set.fins) {
      const double d = std::remainder(roll - fin.roll, 2 * std::numbers::pi);
      if (std::abs(d) < std::abs(nearest)) nearest = d;
    }
    const bool beside = station > 0 && station < profile.length();
    height = rho - (beside ? profile.radius(station) : 0.0);
    offset = rho * std::sin(nearest);
  }
};
}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const geometry::Vehicle vehicle = geometry::preset_vehicle("remus100");
  GridSystem sys = build_grid_system(vehicle, mesh_preset(o.preset, vehicle));
  OversetAssembler assembler(sys, vehicle);
  const double d = o.deflection * std::numbers::pi / 180;
  const Assembly a = assembler.assemble(std::vector<double>(sys.fins.size(), d));
  Context ctx{vehicle, sys, assembler, a, {}, d};
  for (const Grid* g : sys.grids()) ctx.neighbours.push_back(adjacency(*g));

  std::printf("%s preset, every fin at %g deg: %lld cells\n", o.preset.c_str(), o.deflection,
              sys.total_cells());
  std::map<std::string, int> causes;
  for (std::size_t g = 0; g < a.grids.size(); ++g) {
    const auto& ga = a.grids[g];
    std::printf("  grid %zu (%s): %d fringe, %d with fallback donors, %d holes\n", g,
                ctx.kind(g).c_str(), ga.count(CellStatus::fringe), ga.fallbacks(),
                ga.count(CellStatus::hole));
    for (std::size_t c = 0; c < ga.status.size(); ++c) {
      if (ga.status[c] != CellStatus::fringe || !ga.fallback[c]) continue;
      const Eigen::Vector3d x = assembler.centre(static_cast<int>(g), static_cast<int>(c));
      std::string key = ctx.kind(g) + " " + ctx.status(g, static_cast<int>(c)) + " in:";
      for (std::size_t h = 0; h < a.grids.size(); ++h) {
        const int loc = h == g ? -1 : assembler.locate(static_cast<int>(h), x);
        if (loc >= 0) key += " " + ctx.kind(h) + " " + ctx.status(h, loc) + ";";
      }
      ++causes[key];
      if (!o.list) continue;
      double station = 0, height = 0, offset = 0;
      ctx.where(x, station, height, offset);
      std::printf("    grid %zu cell %zu: station %.4f height %.4f offset %.4f: %s\n", g, c,
                  station, height, offset, key.c_str());
    }
  }
  std::vector<std::pair<int, std::string>> sorted;
  for (const auto& [key, n] : causes) sorted.emplace_back(n, key);
  std::sort(sorted.rbegin(), sorted.rend());
  std::printf("fallback receivers by cause (receiver grid, its status, containing cells):\n");
  for (const auto& [n, key] : sorted) std::printf("  %6d  %s\n", n, key.c_str());
}

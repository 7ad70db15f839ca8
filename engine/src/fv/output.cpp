// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/engine/fv/output.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/mesher/grid_io.hpp"

namespace auvloop::engine::fv {

namespace {
bool inside(const Mesh& mesh, int c, const Eigen::Vector3d& x) {
  // Relative to the cell size, so that points on a face count as inside either cell.
  const double tol = 1e-10 * std::cbrt(mesh.volume(c));
  for (int f : mesh.cell_faces(c)) {
    const Eigen::Vector3d n = mesh.area(f).normalized();
    const bool owner = mesh.owner(f) == c;
    // A periodic face lies on the owner's side; the neighbour sees it shifted by its image.
    const Eigen::Vector3d xf =
        owner ? mesh.face_centre(f)
              : Eigen::Vector3d(mesh.face_centre(f) - (mesh.neighbour_centre(f) - mesh.centre(c)));
    if ((owner ? 1.0 : -1.0) * n.dot(x - xf) > tol) return false;
  }
  return true;
}

void write_csv(const std::filesystem::path& csv, const std::string& content) {
  if (csv.has_parent_path()) std::filesystem::create_directories(csv.parent_path());
  write_file_atomically(csv, content);
}
}  // namespace

int find_cell(const Mesh& mesh, const Eigen::Vector3d& x) {
  for (int c = 0; c < mesh.cells(); ++c)
    if (inside(mesh, c, x)) return c;
  return -1;
}

Probes::Probes(const Mesh& mesh, std::vector<Eigen::Vector3d> points)
    : mesh_(mesh), points_(std::move(points)) {
  for (const auto& x : points_) {
    const int c = find_cell(mesh, x);
    if (c < 0)
      throw std::invalid_argument(
          fmt::format("probe point ({:.6g}, {:.6g}, {:.6g}) m is outside "
                      "grid '{}'",
                      x.x(), x.y(), x.z(), mesh.grid().name));
    cells_.push_back(c);
  }
}

std::vector<double> Probes::sample(const ScalarField& phi) const {
  const auto g = grad(mesh_, phi);
  std::vector<double> out;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const int c = cells_[i];
    const auto s = static_cast<std::size_t>(c);
    out.push_back(phi.cells[s] + g[s].dot(points_[i] - mesh_.centre(c)));
  }
  return out;
}

std::vector<Eigen::Vector3d> line_points(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         int n) {
  if (n < 2)
    throw std::invalid_argument("line sample: need at least 2 points, got " + std::to_string(n));
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) out.emplace_back(a + (b - a) * (static_cast<double>(i) / (n - 1)));
  return out;
}

ProbeSeries::ProbeSeries(const Mesh& mesh, std::vector<Eigen::Vector3d> points)
    : probes_(mesh, std::move(points)) {}

void ProbeSeries::record(const Pimple& flow) {
  std::array<std::vector<double>, 4> v{probes_.sample(flow.U.c[0]), probes_.sample(flow.U.c[1]),
                                       probes_.sample(flow.U.c[2]), probes_.sample(flow.p)};
  std::vector<double> row{flow.time()};
  for (std::size_t i = 0; i < probes_.points().size(); ++i)
    for (const auto& field : v) row.push_back(field[i]);
  rows_.push_back(std::move(row));
}

void ProbeSeries::write(const std::filesystem::path& csv) const {
  std::string s = "time";
  for (std::size_t i = 0; i < probes_.points().size(); ++i)
    s += fmt::format(",Ux_{0},Uy_{0},Uz_{0},p_{0}", i);
  s += "\n";
  for (const auto& row : rows_) {
    for (std::size_t k = 0; k < row.size(); ++k)
      s += fmt::format("{}{:.12g}", k ? "," : "", row[k]);
    s += "\n";
  }
  write_csv(csv, s);
}

void write_line_sample(const std::filesystem::path& csv, const Pimple& flow,
                       const Eigen::Vector3d& a, const Eigen::Vector3d& b, int n) {
  const Probes probes(flow.mesh(), line_points(a, b, n));
  std::array<std::vector<double>, 4> v{probes.sample(flow.U.c[0]), probes.sample(flow.U.c[1]),
                                       probes.sample(flow.U.c[2]), probes.sample(flow.p)};
  std::string s = fmt::format("# t = {:.12g} s\ns,x,y,z,Ux,Uy,Uz,p\n", flow.time());
  for (std::size_t i = 0; i < probes.points().size(); ++i) {
    const auto& x = probes.points()[i];
    s += fmt::format("{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g}\n",
                     (x - a).norm(), x.x(), x.y(), x.z(), v[0][i], v[1][i], v[2][i], v[3][i]);
  }
  write_csv(csv, s);
}

VtkSeries::VtkSeries(std::filesystem::path dir, std::string name)
    : dir_(std::move(dir)), name_(std::move(name)) {}

void VtkSeries::write(const Pimple& flow, const std::map<std::string, const ScalarField*>& extra) {
  const Mesh& mesh = flow.mesh();
  const auto n = static_cast<std::size_t>(mesh.cells());
  std::map<std::string, std::vector<double>> fields;
  auto& U = fields["U"];  // 3 values per cell: written as a vector
  U.reserve(3 * n);
  for (std::size_t c = 0; c < n; ++c)
    for (const auto& comp : flow.U.c) U.push_back(comp.cells[c]);
  fields["p"] = flow.p.cells;
  if (const TurbulenceModel* model = flow.turbulence())  // k, omega, nut, ...
    for (const ScalarField* field : model->fields()) fields[field->name] = field->cells;
  for (const auto& [name, field] : extra) {
    if (field == nullptr || field->cells.size() != n)
      throw std::invalid_argument("VTK output: field '" + name + "' has no value per cell");
    fields[name] = field->cells;
  }
  const std::string file = fmt::format("{}_{:06d}.vtu", name_, flow.steps());
  // The grid as given: for periodic grids its cells have their own faces (the coupled grid's
  // periodic faces belong to one side only).
  mesher::write_vtu(dir_ / file, mesh.source_grid(), fields);
  entries_.emplace_back(flow.time(), file);
  std::string xml =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, f] : entries_)
    xml += fmt::format("<DataSet timestep=\"{:.12g}\" part=\"0\" file=\"{}\"/>\n", t, f);
  xml += "</Collection>\n</VTKFile>\n";
  write_file_atomically(pvd(), xml);
}

}  // namespace auvloop::engine::fv

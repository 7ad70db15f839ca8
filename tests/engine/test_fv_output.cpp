// SPDX-License-Identifier: GPL-3.0-or-later
// Probes, line samples and VTK field output. Probe values are second order (cell value plus the
// least-squares gradient times the offset): exact for linear fields on any grid, and converging
// at second order for a smooth field (here sin x cos y, whose values are known everywhere).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "auvloop/engine/fv/output.hpp"
#include "auvloop/geometry/file_io.hpp"
#include "auvloop/mesher/generators.hpp"

using namespace auvloop;
namespace fv = engine::fv;

namespace {
// Graded cells (largest / smallest 3 in x, 1/2 in z whatever n), so refinement halves every cell.
mesher::Grid box(int n) {
  const double rx = std::pow(3.0, 1.0 / (n - 1)), rz = std::pow(0.5, 1.0 / (n - 1));
  return mesher::cartesian_box(mesher::graded_nodes(0, 1, n, rx), mesher::graded_nodes(0, 1, n),
                               mesher::graded_nodes(0, 0.5, n, rz), {}, "box");
}

void set(const fv::Mesh& mesh, fv::ScalarField& f, double (*fn)(const Eigen::Vector3d&)) {
  for (int c = 0; c < mesh.cells(); ++c) f.cells[static_cast<std::size_t>(c)] = fn(mesh.centre(c));
  for (int b = 0; b < mesh.boundary_faces(); ++b)
    f.boundary[static_cast<std::size_t>(b)] = fn(mesh.face_centre(b + mesh.internal_faces()));
}

double linear(const Eigen::Vector3d& x) {
  return 1.5 + 2 * x.x() - 3 * x.y() + 0.7 * x.z();
}
double smooth(const Eigen::Vector3d& x) {
  return std::sin(3 * x.x()) * std::cos(2 * x.y());
}

const std::vector<Eigen::Vector3d> kPoints{
    {0.11, 0.23, 0.37}, {0.5, 0.5, 0.25}, {0.93, 0.07, 0.41}, {0.301, 0.777, 0.05}};

double max_probe_error(int n, double (*fn)(const Eigen::Vector3d&)) {
  const auto grid = box(n);
  const fv::Mesh mesh(grid);
  fv::ScalarField f(mesh, "f");
  set(mesh, f, fn);
  const fv::Probes probes(mesh, kPoints);
  const auto v = probes.sample(f);
  double worst = 0;
  for (std::size_t i = 0; i < kPoints.size(); ++i)
    worst = std::max(worst, std::abs(v[i] - fn(kPoints[i])));
  return worst;
}
}  // namespace

TEST(FvProbes, ExactForLinearFieldsOnGradedCells) {
  EXPECT_LT(max_probe_error(7, linear), 1e-12);
}

TEST(FvProbes, SecondOrderForASmoothField) {
  const double e8 = max_probe_error(8, smooth), e16 = max_probe_error(16, smooth);
  const double e32 = max_probe_error(32, smooth);
  std::printf("probe error: %.3g %.3g %.3g\n", e8, e16, e32);
  EXPECT_GT(std::log2(e16 / e32), 1.8);
}

TEST(FvProbes, FindTheirCellsBesidePeriodicPatches) {
  // The cells next to x+ see their coupled face at x = 1 although it is stored at x = 0.
  mesher::BoxPatches patches;
  patches.types[0] = patches.types[1] = mesher::PatchType::periodic;
  const auto grid =
      mesher::cartesian_box(mesher::graded_nodes(0, 1, 4), mesher::graded_nodes(0, 1, 4),
                            mesher::graded_nodes(0, 1, 4), patches, "periodic");
  const fv::Mesh mesh(grid);
  const fv::Probes probes(mesh, {{0.9, 0.3, 0.6}, {0.1, 0.3, 0.6}});
  EXPECT_EQ(mesh.centre(probes.cells()[0]).x(), 0.875);
  EXPECT_EQ(mesh.centre(probes.cells()[1]).x(), 0.125);
}

TEST(FvProbes, PointOutsideTheGridIsNamed) {
  const auto grid = box(4);
  const fv::Mesh mesh(grid);
  try {
    fv::Probes probes(mesh, {{0.5, 0.5, 0.6}});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(0.5, 0.5, 0.6) m is outside grid 'box'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(fv::line_points({0, 0, 0}, {1, 0, 0}, 1), std::invalid_argument);
}

TEST(FvOutput, SeriesLineSampleAndVtkFiles) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("auvloop_fv_output_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto grid = box(4);
  const fv::Mesh mesh(grid);
  fv::PimpleSettings s;
  s.nu = 0.1;
  s.dt = 0.01;
  fv::Pimple flow(mesh, s);
  set(mesh, flow.p, linear);
  for (int c = 0; c < mesh.cells(); ++c) flow.U.c[0].cells[static_cast<std::size_t>(c)] = 0;
  flow.initialise();
  set(mesh, flow.p, linear);  // initialise() refreshed the boundary values from the cells
  fv::ProbeSeries series(mesh, {kPoints[0], kPoints[1]});
  series.record(flow);
  ASSERT_EQ(series.rows().size(), 1u);
  ASSERT_EQ(series.rows()[0].size(), 9u);  // time + 2 x (Ux, Uy, Uz, p)
  EXPECT_NEAR(series.rows()[0][4], linear(kPoints[0]), 1e-12);
  series.write(dir / "probes.csv");
  const auto csv = read_file_text(dir / "probes.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "time,Ux_0,Uy_0,Uz_0,p_0,Ux_1,Uy_1,Uz_1,p_1");

  fv::write_line_sample(dir / "line.csv", flow, {0, 0.5, 0.25}, {1, 0.5, 0.25}, 5);
  std::istringstream line(read_file_text(dir / "line.csv"));
  std::string row;
  int rows = 0;
  while (std::getline(line, row)) ++rows;
  EXPECT_EQ(rows, 7);  // time comment, header, 5 points

  fv::VtkSeries vtk(dir / "vtk", "flow");
  vtk.write(flow, {{"p_copy", &flow.p}});
  flow.step();
  vtk.write(flow);
  const auto pvd = read_file_text(vtk.pvd());
  EXPECT_NE(pvd.find("timestep=\"0\" part=\"0\" file=\"flow_000000.vtu\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0.01\" part=\"0\" file=\"flow_000001.vtu\""), std::string::npos);
  const auto vtu = read_file_text(dir / "vtk" / "flow_000000.vtu");
  EXPECT_NE(vtu.find("Name=\"U\" NumberOfComponents=\"3\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"p_copy\" NumberOfComponents=\"1\""), std::string::npos);
  EXPECT_NE(vtu.find("NumberOfCells=\"64\""), std::string::npos);
  for (const auto& e : std::filesystem::directory_iterator(dir / "vtk"))  // no temporary left
    EXPECT_TRUE(e.path().extension() == ".vtu" || e.path().extension() == ".pvd") << e.path();
  std::filesystem::remove_all(dir);
}

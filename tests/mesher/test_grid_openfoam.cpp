// SPDX-License-Identifier: GPL-3.0-or-later
// Validation against a peer program: OpenFOAM's checkMesh (Debian package openfoam) reads the
// exported polyMesh of a stretched, distorted box, finds it OK, and reports the same total volume
// and maximum non-orthogonality as auvloop's own measures. Skipped when OpenFOAM is absent
// (install it with AUVLOOP_EXTRA_PACKAGES=openfoam scripts/install-deps.sh).
#include <array>
#include <cstdio>
#include <filesystem>
#include <random>
#include <regex>

#include <gtest/gtest.h>

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/generators.hpp"
#include "auvloop/mesher/grid_io.hpp"
#include "auvloop/mesher/grid_system.hpp"
#include "temp_dir.hpp"

using namespace auvloop::mesher;

namespace {
constexpr const char* kBashrc = "/usr/share/openfoam/etc/bashrc";

std::string check_mesh(const std::filesystem::path& dir) {
  const std::string cmd = "bash -c 'set +u; source " + std::string(kBashrc) +
                          " >/dev/null 2>&1; checkMesh -case " + dir.string() + "' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe) != nullptr) out += buf.data();
  pclose(pipe);
  return out;
}

void write_case(const auvloop::test::TempDir& tmp, const Grid& g) {
  write_openfoam_polymesh(tmp.path(), g);
  tmp.write("system/controlDict",
            "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
            "application checkMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; "
            "deltaT 1;\n"
            "writeControl timeStep; writeInterval 1;\n");
  tmp.write("system/fvSchemes",
            "FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\n"
            "ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { "
            "default none; }\n"
            "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default "
            "linear; }\n"
            "snGradSchemes { default corrected; }\n");
  tmp.write("system/fvSolution",
            "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n");
}

double number_after(const std::string& text, const std::string& label) {
  std::smatch m;
  const std::regex re(label + R"(\s*([-+0-9.eE]+))");
  if (!std::regex_search(text, m, re)) return std::nan("");
  return std::stod(m[1]);
}
}  // namespace

TEST(GridOpenFoam, CheckMeshAgrees) {
  if (!std::filesystem::exists(kBashrc))
    GTEST_SKIP() << "OpenFOAM (Debian package openfoam) is not installed";
  Grid g = cartesian_box(graded_nodes(0, 1, 12, 1.2, true), graded_nodes(0, 1, 10),
                         graded_nodes(0, 0.5, 6, 0.8));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (auto& p : g.points) {
    if (p.minCoeff() > 1e-12 && p.x() < 1 - 1e-12 && p.y() < 1 - 1e-12 && p.z() < 0.5 - 1e-12) {
      p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    }
  }
  auvloop::test::TempDir tmp;
  write_case(tmp, g);
  const std::string out = check_mesh(tmp.path());
  ASSERT_NE(out.find("Mesh OK."), std::string::npos) << out;
  EXPECT_NE(out.find("Upper triangular ordering OK."), std::string::npos);
  const GridQuality q = measure_quality(g, compute_geometry(g));
  EXPECT_NEAR(number_after(out, "Total volume ="), q.total_volume, 1e-6);
  EXPECT_NEAR(number_after(out, "Mesh non-orthogonality Max:"), q.max_non_orthogonality, 1e-3);
  std::printf(
      "checkMesh: max non-orthogonality %.4f deg (auvloop %.4f), total volume %.6g (auvloop "
      "%.6g)\n",
      number_after(out, "Mesh non-orthogonality Max:"), q.max_non_orthogonality,
      number_after(out, "Total volume ="), q.total_volume);
}

// The component grids of the coarse preset (hull, one fin, background): checkMesh finds each one
// OK (closed patches of the hull grid included) and agrees with auvloop on the total volume and
// the worst non-orthogonality.
TEST(GridOpenFoam, CheckMeshAcceptsTheComponentGrids) {
  if (!std::filesystem::exists(kBashrc))
    GTEST_SKIP() << "OpenFOAM (Debian package openfoam) is not installed";
  const auto v = auvloop::geometry::preset_vehicle("remus100");
  const GridSystem sys = build_grid_system(v, mesh_preset("coarse", v));
  for (const Grid* g : {&sys.hull, &sys.fins.front(), &sys.background}) {
    auvloop::test::TempDir tmp;
    write_case(tmp, *g);
    const std::string out = check_mesh(tmp.path());
    EXPECT_NE(out.find("Mesh OK."), std::string::npos) << g->name << "\n" << out;
    const GridQuality q = measure_quality(*g, compute_geometry(*g));
    // checkMesh prints 6 significant digits.
    EXPECT_NEAR(number_after(out, "Total volume ="), q.total_volume, 1e-5 * q.total_volume);
    EXPECT_NEAR(number_after(out, "Mesh non-orthogonality Max:"), q.max_non_orthogonality, 1e-3);
    std::printf(
        "checkMesh %s: %s, max non-orthogonality %.4g deg (auvloop %.4g), max skewness "
        "%.4g (OpenFOAM's measure), total volume %.6g m^3 (auvloop %.6g)\n",
        g->name.c_str(), out.find("Mesh OK.") != std::string::npos ? "Mesh OK" : "FAILED",
        number_after(out, "Mesh non-orthogonality Max:"), q.max_non_orthogonality,
        number_after(out, "Max skewness ="), number_after(out, "Total volume ="), q.total_volume);
  }
}

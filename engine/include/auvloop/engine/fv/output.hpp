// SPDX-License-Identifier: GPL-3.0-or-later
// Output of a solution: point probes, line samples (CSV) and VTK field files (.vtu per time with
// a .pvd collection, for ParaView). Every file is written atomically (temporary file, then
// rename), so a reader never sees a partial file.
//
// A probe's value is second order: phi_P + grad(phi)_P . (x - x_P) in the cell P containing the
// point, with the least-squares gradient (exact for fields linear in space).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "auvloop/engine/fv/pimple.hpp"

namespace auvloop::engine::fv {

// The cell containing x (a point on a shared face: the lower-numbered cell), found by the
// half-space test of each face plane (cells must be convex); -1 when no cell contains it.
int find_cell(const Mesh& mesh, const Eigen::Vector3d& x);

class Probes {
 public:
  // Throws std::invalid_argument naming the first point that lies in no cell.
  Probes(const Mesh& mesh, std::vector<Eigen::Vector3d> points);
  [[nodiscard]] const std::vector<Eigen::Vector3d>& points() const { return points_; }
  [[nodiscard]] const std::vector<int>& cells() const { return cells_; }
  // One value per point.
  [[nodiscard]] std::vector<double> sample(const ScalarField& phi) const;

 private:
  const Mesh& mesh_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<int> cells_;
};

// n >= 2 points evenly spaced from a to b, both ends included.
std::vector<Eigen::Vector3d> line_points(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int n);

// Time series of U and p at fixed points: record() once per step (or as often as wanted),
// write() the whole series as CSV: time, then Ux, Uy, Uz, p of each probe.
class ProbeSeries {
 public:
  ProbeSeries(const Mesh& mesh, std::vector<Eigen::Vector3d> points);
  void record(const Pimple& flow);
  void write(const std::filesystem::path& csv) const;
  [[nodiscard]] const std::vector<std::vector<double>>& rows() const { return rows_; }

 private:
  Probes probes_;
  std::vector<std::vector<double>> rows_;
};

// U and p along the line a -> b at n points at the current time: CSV with columns s (distance
// from a, m), x, y, z, Ux, Uy, Uz, p.
void write_line_sample(const std::filesystem::path& csv, const Pimple& flow,
                       const Eigen::Vector3d& a, const Eigen::Vector3d& b, int n);

// VTK output at chosen times: each write() adds DIR/NAME_<step>.vtu with the cell fields U
// (vector), p and any extra scalars, and rewrites DIR/NAME.pvd listing all files with their times.
class VtkSeries {
 public:
  VtkSeries(std::filesystem::path dir, std::string name);
  void write(const Pimple& flow, const std::map<std::string, const ScalarField*>& extra = {});
  [[nodiscard]] std::filesystem::path pvd() const { return dir_ / (name_ + ".pvd"); }

 private:
  std::filesystem::path dir_;
  std::string name_;
  std::vector<std::pair<double, std::string>> entries_;  // time, file name
};

}  // namespace auvloop::engine::fv

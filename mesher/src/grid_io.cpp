// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/mesher/grid_io.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "auvloop/geometry/file_io.hpp"

namespace auvloop::mesher {
namespace fs = std::filesystem;

namespace {

std::string foam_header(const std::string& cls, const std::string& object) {
  return fmt::format(
      "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {};\n"
      "    location    \"constant/polyMesh\";\n    object      {};\n}}\n// Written by auvloop\n\n",
      cls, object);
}

std::string foam_type(PatchType t) {
  switch (t) {
    case PatchType::wall:
      return "wall";
    case PatchType::symmetry:
      return "symmetry";
    case PatchType::empty:
      return "empty";
    case PatchType::periodic:
      return "cyclic";
    default:
      return "patch";
  }
}

Eigen::Vector3d placed(const Grid& g, int p) {
  return g.placement * g.points[static_cast<std::size_t>(p)];
}

}  // namespace

void write_openfoam_polymesh(const fs::path& case_dir, const Grid& g) {
  const fs::path dir = case_dir / "constant" / "polyMesh";
  fs::create_directories(dir);
  std::string points =
      foam_header("vectorField", "points") + fmt::format("{}\n(\n", g.points.size());
  for (int p = 0; p < static_cast<int>(g.points.size()); ++p) {
    const Eigen::Vector3d x = placed(g, p);
    points += fmt::format("({:.17g} {:.17g} {:.17g})\n", x.x(), x.y(), x.z());
  }
  points += ")\n";
  std::string faces = foam_header("faceList", "faces") + fmt::format("{}\n(\n", g.faces());
  for (int f = 0; f < g.faces(); ++f) {
    faces += fmt::format("{}(", g.face_size(f));
    for (int k = 0; k < g.face_size(f); ++k)
      faces += fmt::format("{}{}", k ? " " : "", g.face_point(f, k));
    faces += ")\n";
  }
  faces += ")\n";
  const std::string note = fmt::format("nPoints:{} nCells:{} nFaces:{} nInternalFaces:{}",
                                       g.points.size(), g.cells, g.faces(), g.internal_faces());
  auto labels = [&](const std::string& object, const std::vector<int>& v) {
    std::string s = foam_header("labelList", object);
    s.insert(s.find("    object"), fmt::format("    note        \"{}\";\n", note));
    s += fmt::format("{}\n(\n", v.size());
    for (int x : v) s += fmt::format("{}\n", x);
    return s + ")\n";
  };
  std::string boundary =
      foam_header("polyBoundaryMesh", "boundary") + fmt::format("{}\n(\n", g.patches.size());
  for (const auto& p : g.patches) {
    boundary +=
        fmt::format("    {}\n    {{\n        type            {};\n", p.name, foam_type(p.type));
    if (p.type == PatchType::periodic && p.neighbour_patch >= 0) {
      boundary += fmt::format("        neighbourPatch  {};\n",
                              g.patches[static_cast<std::size_t>(p.neighbour_patch)].name);
    }
    boundary += fmt::format("        nFaces          {};\n        startFace       {};\n    }}\n",
                            p.size, p.start);
  }
  boundary += ")\n";
  write_file_atomically(dir / "points", points);
  write_file_atomically(dir / "faces", faces);
  write_file_atomically(dir / "owner", labels("owner", g.owner));
  write_file_atomically(dir / "neighbour", labels("neighbour", g.neighbour));
  write_file_atomically(dir / "boundary", boundary);
}

void write_vtu(const fs::path& file, const Grid& g,
               const std::map<std::string, std::vector<double>>& cell_fields) {
  // Each cell's faces, oriented outward (a neighbour sees the owner's face reversed).
  std::vector<std::vector<int>> cell_faces(static_cast<std::size_t>(g.cells));
  for (int f = 0; f < g.faces(); ++f) {
    cell_faces[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(f)])].push_back(f + 1);
    if (f < g.internal_faces())
      cell_faces[static_cast<std::size_t>(g.neighbour[static_cast<std::size_t>(f)])].push_back(
          -(f + 1));
  }
  std::string conn, offsets, faces, faceoffsets, types;
  long n_conn = 0, n_faces = 0;
  for (const auto& fl : cell_faces) {
    std::vector<int> unique;
    faces += fmt::format("{} ", fl.size());
    ++n_faces;
    for (int sf : fl) {
      const int f = std::abs(sf) - 1;
      const int n = g.face_size(f);
      faces += fmt::format("{} ", n);
      ++n_faces;
      for (int k = 0; k < n; ++k) {
        const int p = g.face_point(f, sf > 0 ? k : n - 1 - k);
        faces += fmt::format("{} ", p);
        ++n_faces;
        if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
      }
    }
    faces += "\n";
    for (int p : unique) conn += fmt::format("{} ", p);
    conn += "\n";
    n_conn += static_cast<long>(unique.size());
    offsets += fmt::format("{} ", n_conn);
    faceoffsets += fmt::format("{} ", n_faces);
    types += "42 ";
  }
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n";
  s += fmt::format(
      "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>\n<DataArray type=\"Float64\" "
      "NumberOfComponents=\"3\" format=\"ascii\">\n",
      g.points.size(), g.cells);
  for (int p = 0; p < static_cast<int>(g.points.size()); ++p) {
    const Eigen::Vector3d x = placed(g, p);
    s += fmt::format("{:.10g} {:.10g} {:.10g}\n", x.x(), x.y(), x.z());
  }
  s += "</DataArray>\n</Points>\n<Cells>\n";
  s += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" + conn +
       "</DataArray>\n";
  s += "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n" + offsets +
       "\n</DataArray>\n";
  s += "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n" + types + "\n</DataArray>\n";
  s += "<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">\n" + faces + "</DataArray>\n";
  s += "<DataArray type=\"Int64\" Name=\"faceoffsets\" format=\"ascii\">\n" + faceoffsets +
       "\n</DataArray>\n";
  s += "</Cells>\n<CellData>\n";
  for (const auto& [name, values] : cell_fields) {
    // One value per cell, or three (a vector, x y z per cell in turn).
    const auto cells = static_cast<std::size_t>(g.cells);
    if (values.size() != cells && values.size() != 3 * cells)
      throw std::invalid_argument(fmt::format("write_vtu: field '{}' has {} values for {} cells",
                                              name, values.size(), cells));
    s += fmt::format(
        "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
        name, values.size() == cells ? 1 : 3);
    for (double v : values) s += fmt::format("{:.10g} ", v);
    s += "\n</DataArray>\n";
  }
  s += "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  write_file_atomically(file, s);
}

void write_vtm(const fs::path& dir, const std::string& name, const std::vector<const Grid*>& grids,
               const std::vector<std::map<std::string, std::vector<double>>>& cell_fields) {
  std::string vtm =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <vtkMultiBlockDataSet>\n";
  for (std::size_t i = 0; i < grids.size(); ++i) {
    const std::string file = grids[i]->name + ".vtu";
    write_vtu(dir / file, *grids[i],
              i < cell_fields.size() ? cell_fields[i] : decltype(cell_fields[0]){});
    vtm += fmt::format("    <DataSet index=\"{}\" name=\"{}\" file=\"{}\"/>\n", i, grids[i]->name,
                       file);
  }
  vtm += "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
  write_file_atomically(dir / (name + ".vtm"), vtm);
}

}  // namespace auvloop::mesher

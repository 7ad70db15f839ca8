// SPDX-License-Identifier: GPL-3.0-or-later
#include "auvloop/geometry/surface_io.hpp"

#include <array>
#include <map>
#include <random>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <fmt/std.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include "auvloop/geometry/error.hpp"

namespace auvloop::geometry {
namespace fs = std::filesystem;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace {

struct Format {
  std::string_view extension;
  std::string_view assimp_id;
};
// Binary variants where assimp has them: smaller files and exact float32 coordinates.
constexpr std::array<Format, 5> kFormats{{{".stl", "stlb"},
                                          {".obj", "objnomtl"},
                                          {".ply", "plyb"},
                                          {".gltf", "gltf2"},
                                          {".glb", "glb2"}}};

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

const Format& format_for(const fs::path& path) {
  const std::string ext = lower_extension(path);
  for (const auto& f : kFormats) {
    if (f.extension == ext) return f;
  }
  std::string known;
  for (const auto& f : kFormats) known += (known.empty() ? "" : ", ") + std::string(f.extension);
  throw GeometryError(fmt::format("{}: unsupported surface format \"{}\" (supported: {})", path,
                                  ext.empty() ? "no extension" : ext, known));
}

aiMesh* to_assimp(const SurfacePart& part) {
  auto* m = new aiMesh();
  m->mName = aiString(part.name);
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mMaterialIndex = 0;
  std::map<SurfaceMesh::Vertex_index, unsigned> index;
  m->mNumVertices = static_cast<unsigned>(part.mesh.number_of_vertices());
  m->mVertices = new aiVector3D[m->mNumVertices];
  unsigned k = 0;
  for (auto v : part.mesh.vertices()) {
    const auto& p = part.mesh.point(v);
    m->mVertices[k] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()),
                                 static_cast<ai_real>(p.z()));
    index[v] = k++;
  }
  m->mNumFaces = static_cast<unsigned>(part.mesh.number_of_faces());
  m->mFaces = new aiFace[m->mNumFaces];
  unsigned f = 0;
  for (auto face : part.mesh.faces()) {
    aiFace& out = m->mFaces[f++];
    out.mNumIndices = 3;
    out.mIndices = new unsigned[3];
    unsigned j = 0;
    for (auto v : CGAL::vertices_around_face(part.mesh.halfedge(face), part.mesh)) {
      if (j < 3) out.mIndices[j] = index.at(v);
      ++j;
    }
    if (j != 3)
      throw GeometryError(fmt::format("part \"{}\" has a face that is not a triangle", part.name));
  }
  return m;
}

// A scene with one node and one mesh per part; the scene's destructor frees all of it.
std::unique_ptr<aiScene> make_scene(std::span<const SurfacePart> parts) {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene->mNumMeshes = static_cast<unsigned>(parts.size());
  scene->mMeshes = new aiMesh* [parts.size()] {};
  scene->mRootNode = new aiNode("auvloop");
  scene->mRootNode->mNumChildren = static_cast<unsigned>(parts.size());
  scene->mRootNode->mChildren = new aiNode* [parts.size()] {};
  for (unsigned i = 0; i < parts.size(); ++i) {
    scene->mMeshes[i] = to_assimp(parts[i]);
    auto* node = new aiNode(parts[i].name);
    node->mParent = scene->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{i};
    scene->mRootNode->mChildren[i] = node;
  }
  return scene;
}

fs::path scratch_directory(const fs::path& target) {
  std::random_device rd;
  const fs::path dir =
      target.parent_path() / fmt::format(".{}.tmp-{:08x}", target.filename().string(), rd());
  fs::create_directories(dir);
  return dir;
}

}  // namespace

std::vector<std::string> surface_file_extensions() {
  std::vector<std::string> out;
  for (const auto& f : kFormats) out.emplace_back(f.extension);
  return out;
}

void write_surface(const fs::path& path, std::span<const SurfacePart> parts) {
  const Format& format = format_for(path);
  if (parts.empty()) throw GeometryError(fmt::format("{}: nothing to write", path));
  const fs::path target = fs::absolute(path);
  fs::create_directories(target.parent_path());
  // Export into a private directory next to the target, then rename each file into place (a
  // .gltf also writes a .bin), the main file last: readers never see a partial file.
  const fs::path scratch = scratch_directory(target);
  try {
    const auto scene = make_scene(parts);
    Assimp::Exporter exporter;
    const fs::path staged = scratch / target.filename();
    if (exporter.Export(scene.get(), std::string(format.assimp_id), staged.string()) !=
        AI_SUCCESS) {
      throw GeometryError(fmt::format("{}: export failed: {}", path, exporter.GetErrorString()));
    }
    for (const auto& entry : fs::directory_iterator(scratch)) {
      if (entry.path() != staged)
        fs::rename(entry.path(), target.parent_path() / entry.path().filename());
    }
    fs::rename(staged, target);
    fs::remove_all(scratch);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(scratch, ec);
    throw;
  }
}

namespace {

struct Soup {
  std::string name;
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::size_t non_triangles = 0;
};

// Adds the triangles of one assimp mesh, transformed to the file's root frame and scaled, with
// vertices welded where their coordinates coincide exactly (STL and OBJ store each face's
// corners separately).
void append_mesh(Soup& soup, const aiMesh& mesh, const aiMatrix4x4& transform, double scale) {
  std::map<std::array<double, 3>, std::size_t> weld;
  for (const auto& p : soup.points) weld.emplace(std::array{p.x(), p.y(), p.z()}, weld.size());
  std::vector<std::size_t> id(mesh.mNumVertices);
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D v = transform * mesh.mVertices[i];
    const std::array<double, 3> key{scale * static_cast<double>(v.x),
                                    scale * static_cast<double>(v.y),
                                    scale * static_cast<double>(v.z)};
    auto [it, inserted] = weld.emplace(key, soup.points.size());
    if (inserted) soup.points.emplace_back(key[0], key[1], key[2]);
    id[i] = it->second;
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) {
      ++soup.non_triangles;
      continue;
    }
    soup.triangles.push_back({id[face.mIndices[0]], id[face.mIndices[1]], id[face.mIndices[2]]});
  }
}

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, double scale,
             std::vector<Soup>& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    Soup soup;
    soup.name = mesh.mName.length > 0 ? mesh.mName.C_Str() : node.mName.C_Str();
    if (soup.name.empty()) soup.name = fmt::format("part{}", out.size());
    append_mesh(soup, mesh, transform, scale);
    out.push_back(std::move(soup));
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i)
    collect(scene, *node.mChildren[i], transform, scale, out);
}

// Edge-use analysis of a triangle soup: what a half-edge mesh cannot even represent.
SurfaceDefects soup_defects(const Soup& soup) {
  SurfaceDefects d;
  std::map<std::pair<std::size_t, std::size_t>, std::array<int, 2>>
      uses;  // (lo, hi) -> {lo->hi, hi->lo}
  for (const auto& t : soup.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      ++d.degenerate_faces;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = t[static_cast<std::size_t>(k)],
                        b = t[static_cast<std::size_t>((k + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}][a < b ? 0 : 1];
    }
  }
  for (const auto& [edge, n] : uses) {
    const int total = n[0] + n[1];
    if (total == 1) ++d.boundary_edges;
    if (total > 2) ++d.non_manifold;
    if (total == 2 && n[0] != 1) ++d.misoriented_edges;
  }
  return d;
}

SurfacePart to_part(const Soup& soup, const SurfaceReadOptions& options,
                    std::vector<std::string>& problems) {
  SurfaceDefects d = soup_defects(soup);
  SurfacePart part{soup.name, {}};
  if (soup.non_triangles > 0) {
    problems.push_back(fmt::format("part \"{}\": {} faces are lines or points, not triangles",
                                   soup.name, soup.non_triangles));
  }
  if (d.boundary_edges == 0 && d.non_manifold == 0 && d.misoriented_edges == 0 &&
      d.degenerate_faces == 0) {
    if (!PMP::is_polygon_soup_a_polygon_mesh(soup.triangles)) {
      d.non_manifold = 1;  // pinched vertex: edges are fine, but a vertex joins two fans
    } else {
      PMP::polygon_soup_to_polygon_mesh(soup.points, soup.triangles, part.mesh);
      d = inspect(part.mesh);
      if (!options.check_self_intersection) d.self_intersecting = false;
    }
  }
  if (!d.ok()) {
    std::string text = d.describe();
    std::string::size_type pos = 0;
    while (pos != std::string::npos) {
      const auto end = text.find('\n', pos);
      problems.push_back(fmt::format("part \"{}\": {}", soup.name, text.substr(pos, end - pos)));
      pos = end == std::string::npos ? end : end + 1;
    }
  }
  return part;
}

void check_extent(const fs::path& path, const std::vector<Soup>& soups,
                  const SurfaceReadOptions& options) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& s : soups) {
    for (const auto& p : s.points) {
      lo = lo.cwiseMin(Eigen::Vector3d(p.x(), p.y(), p.z()));
      hi = hi.cwiseMax(Eigen::Vector3d(p.x(), p.y(), p.z()));
    }
  }
  const double extent = (hi - lo).maxCoeff();
  if (!(extent >= options.min_extent && extent <= options.max_extent)) {
    const double hint = extent > options.max_extent ? 0.001 : 1000.0;
    throw GeometryError(
        fmt::format("{}: implausible size: the surface spans {:.6g} units, but auvloop reads "
                    "metres and expects "
                    "a vehicle between {:g} m and {:g} m; if the file is in {} use a scale of {:g} "
                    "(--scale {:g})",
                    path, extent, options.min_extent, options.max_extent,
                    extent > options.max_extent ? "millimetres" : "kilometres or other large units",
                    hint, hint));
  }
}

}  // namespace

std::vector<SurfacePart> read_surface(const fs::path& path, const SurfaceReadOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw GeometryError(fmt::format("{}: no such file", path));
  if (!fs::is_regular_file(path, ec))
    throw GeometryError(fmt::format("{}: not a regular file", path));
  if (fs::file_size(path, ec) == 0) throw GeometryError(fmt::format("{}: the file is empty", path));
  format_for(path);  // rejects unsupported extensions with the list of supported ones
  if (!(options.scale > 0)) throw GeometryError(fmt::format("{}: scale must be positive", path));

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw GeometryError(
        fmt::format("{}: not a readable surface file: {}", path,
                    scene == nullptr ? importer.GetErrorString() : "incomplete scene"));
  }
  std::vector<Soup> soups;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), options.scale, soups);
  std::erase_if(soups, [](const Soup& s) { return s.triangles.empty() && s.non_triangles == 0; });
  if (soups.empty()) throw GeometryError(fmt::format("{}: the file contains no triangles", path));
  check_extent(path, soups, options);

  std::vector<std::string> problems;
  std::vector<SurfacePart> parts;
  for (const auto& soup : soups) parts.push_back(to_part(soup, options, problems));
  if (!problems.empty()) {
    std::string message = fmt::format("{}: the surface cannot be used:", path);
    for (const auto& p : problems) message += "\n  " + p;
    throw GeometryError(message);
  }
  return parts;
}

}  // namespace auvloop::geometry

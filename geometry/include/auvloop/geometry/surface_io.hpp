// SPDX-License-Identifier: GPL-3.0-or-later
// Surface-mesh files through assimp. The format follows the file extension:
//   .stl (binary), .obj, .ply (binary), .gltf (+ .bin), .glb
// Writes are atomic: the files appear under their final names only when complete.
// Reads check that every part is closed, manifold, consistently and outwardly oriented, free of
// degenerate faces and of plausible size for metres, and report every problem with the file name.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "auvloop/geometry/surface.hpp"

namespace auvloop::geometry {

std::vector<std::string> surface_file_extensions();  // {".stl", ".obj", ...}

void write_surface(const std::filesystem::path& path, std::span<const SurfacePart> parts);

struct SurfaceReadOptions {
  double scale = 1.0;  // multiply coordinates by this (0.001 for a file in millimetres)
  // Largest extent of a plausible vehicle, after scaling (m); outside it the file is assumed to be
  // in other units and rejected with a hint about `scale`.
  double min_extent = 0.05;
  double max_extent = 100.0;
  bool check_self_intersection = true;
};

// Throws GeometryError naming the file, the part and every defect found.
std::vector<SurfacePart> read_surface(const std::filesystem::path& path,
                                      const SurfaceReadOptions& options = {});

}  // namespace auvloop::geometry

// SPDX-License-Identifier: GPL-3.0-or-later
// The flat-plate grid (flat_plate_grid.hpp):
//   1. node lists of the finest level: y geometric from first_height at the wall; x geometric
//      from leading_edge_dx at x = 0 along the plate, and mirrored ahead of it;
//   2. every 2^level-th node for the level asked for;
//   3. the tensor-product box (cartesian_box), its y = 0 side split into the symmetry plane ahead
//      of the leading edge and the plate (the side's faces run in x order on a one-cell-thick
//      grid, so the split is where x crosses 0).
#include "auvloop/mesher/flat_plate_grid.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "auvloop/mesher/generators.hpp"

namespace auvloop::mesher {
namespace {
std::vector<double> every(const std::vector<double>& nodes, int stride) {
  std::vector<double> out;
  for (std::size_t i = 0; i < nodes.size(); i += static_cast<std::size_t>(stride))
    out.push_back(nodes[i]);
  return out;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("flat plate grid: " + what);
}
}  // namespace

Grid flat_plate(const FlatPlateSpec& s, int level, const std::string& name) {
  require(s.plate_length > 0 && s.upstream > 0 && s.height > 0 && s.thickness > 0,
          "plate_length, upstream, height and thickness must be positive");
  require(level >= 0 && level < 16, "level must be in [0, 15], got " + std::to_string(level));
  const int stride = 1 << level;
  for (const auto& [count, label] :
       {std::pair{s.plate_cells, "plate_cells"}, std::pair{s.upstream_cells, "upstream_cells"},
        std::pair{s.normal_cells, "normal_cells"}})
    require(count >= stride && count % stride == 0,
            std::string(label) + " = " + std::to_string(count) +
                " must be a positive multiple of " + std::to_string(stride) + " for level " +
                std::to_string(level));
  // 1. The finest level (stretched_nodes checks that each first cell fits its side).
  const auto y = stretched_nodes(0, s.height, s.first_height, s.normal_cells);
  const auto plate = stretched_nodes(0, s.plate_length, s.leading_edge_dx, s.plate_cells);
  const auto ahead = stretched_nodes(0, s.upstream, s.leading_edge_dx, s.upstream_cells);
  std::vector<double> x;
  for (std::size_t i = ahead.size(); i-- > 1;) x.push_back(-ahead[i]);
  x.insert(x.end(), plate.begin(), plate.end());
  // 2. The level's nodes: x = 0 stays a node, as upstream_cells is a multiple of the stride.
  const auto xs = every(x, stride), ys = every(y, stride);
  // 3. The box and its split wall side.
  BoxPatches patches;
  patches.names = {"inlet", "outlet", "symmetry", "top", "front", "back"};
  patches.types = {PatchType::inlet, PatchType::outlet, PatchType::symmetry,
                   s.top_type,       PatchType::empty,  PatchType::empty};
  Grid g = cartesian_box(xs, ys, {0.0, s.thickness}, patches, name);
  const int ahead_faces = s.upstream_cells / stride;
  const auto bottom = static_cast<std::size_t>(2);
  Patch wall{"plate", PatchType::wall, g.patches[bottom].start + ahead_faces,
             g.patches[bottom].size - ahead_faces, -1};
  g.patches[bottom].size = ahead_faces;
  g.patches.insert(g.patches.begin() + 3, wall);
  return g;
}

}  // namespace auvloop::mesher

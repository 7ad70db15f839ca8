// SPDX-License-Identifier: GPL-3.0-or-later
// The composite grid: the algorithm (steps 1-3) is stated in auvloop/mesher/composite_grid.hpp.
#include "auvloop/mesher/composite_grid.hpp"

#include <set>
#include <stdexcept>
#include <string>

namespace auvloop::mesher {

CompositeGrid composite_grid(std::span<const Grid* const> components) {
  if (components.empty()) throw std::invalid_argument("composite grid: no component grids");
  std::set<std::string> names;
  for (const Grid* g : components)
    if (!names.insert(g->name).second)
      throw std::invalid_argument("composite grid: two components named '" + g->name + "'");
  CompositeGrid out;
  Grid& c = out.grid;
  c.name = "composite";
  std::vector<int> point_offset;
  // 1, 2.
  for (const Grid* g : components) {
    out.cell_offset.push_back(c.cells);
    point_offset.push_back(static_cast<int>(c.points.size()));
    Zone zone{g->name, {}};
    for (int k = 0; k < g->cells; ++k) zone.cells.push_back(c.cells + k);
    c.zones.push_back(std::move(zone));
    for (const Zone& z : g->zones) {
      Zone moved{g->name + "/" + z.name, z.cells};
      for (int& cell : moved.cells) cell += c.cells;
      c.zones.push_back(std::move(moved));
    }
    for (const auto& p : g->points) c.points.push_back(g->placement * p);
    c.cells += g->cells;
  }
  std::vector<int> pts;  // one face's points, reused
  const auto add = [&](std::size_t gi, int f) {
    const Grid& g = *components[gi];
    pts.clear();
    for (int k = 0; k < g.face_size(f); ++k) pts.push_back(g.face_point(f, k) + point_offset[gi]);
    c.add_face(pts, g.owner[static_cast<std::size_t>(f)] + out.cell_offset[gi]);
  };
  // 3: internal faces, then the patches.
  for (std::size_t gi = 0; gi < components.size(); ++gi) {
    const Grid& g = *components[gi];
    out.internal_face_offset.push_back(c.faces());
    for (int f = 0; f < g.internal_faces(); ++f) {
      add(gi, f);
      c.neighbour.push_back(g.neighbour[static_cast<std::size_t>(f)] + out.cell_offset[gi]);
    }
  }
  for (std::size_t gi = 0; gi < components.size(); ++gi) {
    const Grid& g = *components[gi];
    out.patch.emplace_back();
    const int first_patch = static_cast<int>(c.patches.size());
    for (const Patch& p : g.patches) {
      out.patch.back().push_back(static_cast<int>(c.patches.size()));
      Patch q{g.name + "/" + p.name, p.type, c.faces(), p.size,
              p.neighbour_patch < 0 ? -1 : p.neighbour_patch + first_patch};
      for (int f = p.start; f < p.start + p.size; ++f) add(gi, f);
      c.patches.push_back(std::move(q));
    }
  }
  return out;
}

CompositeStencils composite_stencils(const CompositeGrid& composite, const Assembly& assembly) {
  const auto& grids = assembly.grids;
  if (grids.size() != composite.cell_offset.size())
    throw std::invalid_argument("composite stencils: the assembly has " +
                                std::to_string(grids.size()) + " grids, the composite " +
                                std::to_string(composite.cell_offset.size()));
  CompositeStencils out;
  out.status.reserve(static_cast<std::size_t>(composite.grid.cells));
  out.offsets.reserve(static_cast<std::size_t>(composite.grid.cells) + 1);
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const GridAssembly& a = grids[g];
    if (a.status.size() != static_cast<std::size_t>(composite.cells_of(g)) ||
        a.stencil_offsets.size() != a.status.size() + 1)
      throw std::invalid_argument("composite stencils: grid " + std::to_string(g) + " has " +
                                  std::to_string(a.status.size()) + " statuses for " +
                                  std::to_string(composite.cells_of(g)) + " cells");
    for (std::size_t c = 0; c < a.status.size(); ++c) {
      out.status.push_back(a.status[c]);
      for (int e = a.stencil_offsets[c]; e < a.stencil_offsets[c + 1]; ++e) {
        const auto s = static_cast<std::size_t>(e);
        out.donors.push_back(composite.cell_offset[static_cast<std::size_t>(a.stencil_grids[s])] +
                             a.stencil_cells[s]);
        out.weights.push_back(a.stencil_weights[s]);
      }
      out.offsets.push_back(static_cast<int>(out.donors.size()));
    }
  }
  return out;
}

CompositeSystem composite_system(const std::vector<OversetComponent>& components,
                                 OversetSettings settings) {
  OversetAssembler assembler(components, settings);
  const auto assembly = assembler.assemble();
  std::vector<const Grid*> grids;
  grids.reserve(components.size());
  for (const auto& c : components) grids.push_back(c.grid);
  CompositeSystem system{composite_grid(grids), {}};
  system.stencils = composite_stencils(system.composite, assembly);
  return system;
}

}  // namespace auvloop::mesher

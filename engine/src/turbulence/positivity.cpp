// SPDX-License-Identifier: GPL-3.0-or-later
// Positivity of k and omega: steps 1-2 of positivity.hpp.
#include "positivity.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

#include "../fv/parallel.hpp"

namespace auvloop::engine::turbulence {

namespace {
// fn(face, neighbour) for every internal face of cell c whose other cell is in the flow, in
// ascending face order.
template <class Fn>
void for_in_flow_neighbours(const fv::Mesh& mesh, const fv::Overset* overset, int c, Fn&& fn) {
  const int internal = mesh.internal_faces();
  for (int f : mesh.cell_faces(c)) {
    if (f >= internal) continue;
    const int o = mesh.owner(f) == c ? mesh.neighbour(f) : mesh.owner(f);
    if (overset != nullptr && !overset->in_flow(o)) continue;
    fn(f, static_cast<std::size_t>(o));
  }
}
}  // namespace

void sink_reference(const fv::Mesh& mesh, const fv::Overset* overset,
                    const std::vector<double>& phi, double floor, std::vector<double>& ref) {
  ref.resize(phi.size());
  fv::parallel_for(mesh.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    double sum = 0, weight = 0;
    bool minimum = true;
    for_in_flow_neighbours(mesh, overset, cell, [&](int f, std::size_t o) {
      minimum = minimum && phi[s] <= phi[o];
      sum += mesh.alpha(f) * phi[o];
      weight += mesh.alpha(f);
    });
    const double mean = minimum && weight > 0 ? sum / weight : 0.0;
    ref[s] = std::max({phi[s], mean, floor});
  });
}

long bound(const fv::Mesh& mesh, const fv::Overset* overset, std::vector<double>& phi, double floor,
           std::vector<double>& scratch) {
  scratch.resize(phi.size());
  const auto raised =  // a count: sums of integers, exact in any order
      fv::parallel_sum<1>(mesh.cells(), [&](int b, int e, std::array<double, 1>& count) {
        for (int cell = b; cell < e; ++cell) {
          const auto s = static_cast<std::size_t>(cell);
          if (phi[s] >= floor) continue;
          double sum = 0, area = 0;
          for_in_flow_neighbours(mesh, overset, cell, [&](int f, std::size_t o) {
            const double a = mesh.area(f).norm();
            sum += a * std::max(phi[o], floor);
            area += a;
          });
          scratch[s] = area > 0 ? std::max(sum / area, floor) : floor;
          count[0] += 1;
        }
      });
  if (raised[0] == 0) return 0;
  fv::parallel_for(mesh.cells(), [&](int cell) {
    const auto s = static_cast<std::size_t>(cell);
    if (!(phi[s] >= floor)) phi[s] = scratch[s];
  });
  return static_cast<long>(raised[0]);
}

}  // namespace auvloop::engine::turbulence

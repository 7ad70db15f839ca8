// SPDX-License-Identifier: GPL-3.0-or-later
// fvm::ddt: backward differences (BDF2, or Euler to start; variable-step coefficients in
// operators.hpp): diag += c0 V / dt, source -= V / dt (c1 phi_old + c2 phi_oldold), per cell.
#include "auvloop/engine/fv/operators.hpp"
#include "parallel.hpp"

namespace auvloop::engine::fv {

void DdtTerm::add_to(Matrix& eq, double sign) const {
  const auto c = ts.coeffs();
  parallel_for(m->cells(), [&](int i) {
    const auto s = static_cast<std::size_t>(i);
    const double vdt = sign * m->volume(i) / ts.dt;
    eq.diag[s] += c[0] * vdt;
    eq.source[s] -= vdt * (c[1] * old[s] + (c[2] != 0.0 ? c[2] * oldold[s] : 0.0));
  });
}

}  // namespace auvloop::engine::fv

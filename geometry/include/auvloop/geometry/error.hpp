// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <stdexcept>

namespace auvloop::geometry {

// A geometric impossibility (a fin root that leaves the hull, a failed boolean union) or a surface
// file that cannot be used (open, non-manifold, unreadable). The message names the file or part.
class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace auvloop::geometry

// SPDX-License-Identifier: GPL-3.0-or-later
// The body-fitted hull grid: a 2D meridional grid around the Myring profile revolved about the
// body x axis (docs/mesher.md).
//
// Meridional topology: one structured block wrapped around the half-profile, from the nose-face
// centre on the axis, up the flat nose face, along the curved hull, down the flat tail face to the
// tail-face centre on the axis (index i), and outward along straight wall-normal lines (index j)
// to `extent`, with a fan of lines round each rim (the convex corner between end face and hull).
// The two end lines lie on the axis ahead of the nose and behind the tail, so the revolved cells
// next to them are prisms (their axis edge collapses), never zero-area faces. Wall points lie
// exactly on the analytic profile. Patches: "hull" (wall: nose face, curved hull, tail face) and
// "hull_overset" (the outer boundary).
#pragma once

#include "auvloop/geometry/myring.hpp"
#include "auvloop/mesher/grid.hpp"

namespace auvloop::mesher {

struct HullGridSpec {
  int nose_face_cells = 6;       // along the flat nose face, axis to rim
  int body_cells = 64;           // along the curved profile, nose rim to tail rim
  int tail_face_cells = 4;       // along the flat tail face, rim to axis
  int circumferential = 32;      // around the axis; a multiple of 4 (cruciform symmetry)
  int normal_cells = 0;          // wall to outer boundary; 0: the fewest that keep `growth`
  double first_cell = 5e-4;      // m, wall-normal height of the first cell
  double growth = 1.2;           // largest ratio of neighbouring wall-normal sizes (normal_cells 0)
  double extent = 0.08;          // m, distance from the wall to the outer boundary
  double rim_clustering = 1.06;  // cell growth away from the nose and tail rims along the wall
  int rim_fan = 6;               // lines fanning round each rim (end face to curved hull)
  // Fillet radius (m) rounding each rim: 0 keeps the sharp corner of the truncated Myring profile
  // with its fan of wedge cells (collapsed on the rim circle); above 0 each rim is a circular arc
  // tangent to the end face and to the curved hull, gridded with `rim_fan` cells whose wall lines
  // are its radii, and the end faces' and the hull's wall cells grade down to the arc's cell size
  // next to it (the faces one-sided, the hull by two_sided_nodes), instead of by rim_clustering.
  // The corner a sharp rim leaves is singular in potential flow; with wall cells of y+ 5 or less
  // its wedges are three orders of magnitude smaller than their neighbours (docs/mesher.md).
  double rim_radius = 0;
  // Equally spaced fins (0: none) and the polar angle (rad, from +y towards +z) of the first:
  // sectors narrow by the factor 1 - fin_clustering at each fin plane and widen between them
  // (theta = xi - c sin(fins (xi - fin_angle)) / fins, c = fin_clustering), so that the hull cells
  // straddling a fin, and the fringe round them, stay close to it (docs/mesher.md).
  int fins = 0;
  double fin_angle = 0;
  double fin_clustering = 0.3;
  // Stern zone over the fins (stations, m aft of the nose; begin >= end: none, and the clustering
  // applies along the whole hull). A share of the body cells is spread evenly over the zone, and
  // the clustering applies there only, fading out over `fin_zone_ramp` either side (cos^2): the
  // hull cells round the fins, whose fringe must stay clear of the fin grids' fringes, come out
  // about half as long and narrower; elsewhere the sectors are even and the rings a little farther
  // apart. build_grid_system sets the zone to the fins' planform.
  double fin_zone_begin = 0;
  double fin_zone_end = 0;
  double fin_zone_share = 0.15;
  double fin_zone_ramp = 0.1;  // m
};

// The grid frame is the body frame (origin at CB, x forward); throws std::invalid_argument naming
// the offending setting when the spec is unusable.
Grid hull_grid(const geometry::MyringProfile& profile, double cb_station, const HullGridSpec& spec);

}  // namespace auvloop::mesher

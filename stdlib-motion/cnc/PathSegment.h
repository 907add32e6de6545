// A decoded element as a segment of the path geometry (stdlib-motion/path): the
// exact curve the interpolators run along, evaluated by path length.  Shared by
// the time-based interpolators (Interpolator, Interpolator2Dir) and the
// position-based XInterpolator (docs/cnc.md, "SMC_Interpolator").
#pragma once

#include "stdlib-motion/cnc/Element.h"
#include "stdlib-motion/path/Geometry.h"

namespace stc::cnc {

namespace path = stc::motion::path;

// All 11 axes (X Y Z A B C P Q U V W) as path coordinates.
constexpr int kPathDims = kAxisCount;
static_assert(kPathDims <= path::kMaxCoords);

inline path::Vec toPathVec(const Pos& p) {
  path::Vec v{};
  for (int i = 0; i < kPathDims; ++i) v[i] = p[i];
  return v;
}

// The segment of a motion element from its own start point: lines and G0 exact;
// arcs and helices exact (centre, normal, sweep and whole turns); G8/G9 ellipses
// exact in X/Y; G5/G10 splines and G6 parabolas as the cubic / quadratic
// polynomial in u that Geometry.h evaluates.  FALSE when the element cannot be
// built (degenerate or non-finite geometry, a non-motion type).
bool buildPathSegment(const Element& e, path::Segment& out);

}  // namespace stc::cnc

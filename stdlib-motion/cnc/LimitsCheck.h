// The workspace check of the path (SMC_CheckForLimits, docs/cnc.md): does an
// element leave the box [min, max] in one of the checked axes?
//
// Bounds are exact for every element type: lines by their end points, arcs,
// helices and ellipses by the critical angles of A cos t + B sin t + C t, splines
// and parabolas by the roots of their polynomial derivatives; the additional axes
// move linearly.
#pragma once

#include <cstdint>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

// The smallest box holding every point of `e` (all axes).  Non-motion elements
// (M, dwell, G75, G92) have the empty box lo > hi: they do not move.
void elementBounds(const Element& e, Pos& lo, Pos& hi);

// Bit per Axis (bit 0 X ... bit 10 W, SMC_POSINFO.wAuxData's order) of the axes in
// `axisMask` where `e` goes below min or above max by more than a rounding
// tolerance of 1e-9 x max(1, |limit|): a path exactly at the limit passes.
uint16_t axesOutOfLimits(const Element& e, const Pos& min, const Pos& max, uint16_t axisMask);

}  // namespace stc::cnc

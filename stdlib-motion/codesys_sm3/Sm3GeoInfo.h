// cnc::Element <-> SMC_GEOINFO (sm3_cnc_types.st; docs/cnc.md, "SMC_GEOINFO").
// The mapping is lossless: fromGeoInfo(toGeoInfo(e)) == e for every element the
// decoder produces, so the later pipeline blocks (tool correction, smoothing, the
// interpolator) can work on cnc::Element and write their results back.
#pragma once

#include "sm3_native.h"
#include "stdlib-motion/cnc/Element.h"

namespace stc::motion::sm3face {

// Fills `g` completely from `e` (every member of g is written).
void toGeoInfo(const cnc::Element& e, native::sm3::SMC_GEOINFO& g);
// The element `g` describes.  False (and `e` unspecified) if `g` is not one
// toGeoInfo could have written: an unknown move type, a switch count above 8, a plane,
// side or smoothing code out of range, a spline dimension other than 2 or 3.
bool fromGeoInfo(const native::sm3::SMC_GEOINFO& g, cnc::Element& e);

// Field-by-field equality of elements (the geometry of the element's type only).
bool sameElement(const cnc::Element& a, const cnc::Element& b);

}  // namespace stc::motion::sm3face

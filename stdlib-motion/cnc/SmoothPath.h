// Corner smoothing (G51) and corner rounding (G52) of the path: SMC_SmoothPath
// (docs/cnc.md, "SMC_SmoothPath").
//
// A corner between two tool-path elements that both have smoothing on is cut at
// the distance d = edgeDistance + D (the G51/G52 D word) from the corner on both
// elements, and the gap is closed by
//  - G51: a cubic Hermite spline (MoveType::Spline, 3D) whose tangent magnitude
//    is 3 d: between two lines it is the cubic Bezier with both inner control
//    points at the corner, so position, tangent AND curvature (zero) are
//    continuous: at constant path velocity the acceleration does not jump.
//    Next to an arc the spline is tangent-continuous (the curvature jumps).
//  - G52: a circular arc tangent to both lines (radius d / tan(turn / 2)), between
//    two lines only (position and tangent continuous).
// d is clamped to half of each element's length (so the two corners of an
// element never overlap); G52 and bSymmetricalDistances use the smaller of the
// two clamped distances on both sides.
#pragma once

#include <cstdint>
#include <vector>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

struct SmoothOptions {
  double edgeDistance = 0;   // dEdgeDistance, added to the D word
  double angleTolDeg = 0;    // dAngleTol: corners turning by at most this (degrees) stay as they are
  bool symmetric = false;    // bSymmetricalDistances
};
// TRUE if the options are finite, not negative, the distance at most 1e9 and the angle at most 180.
bool validOptions(const SmoothOptions& o);

// The part of a line or an arc (helix) between the parameters u0 < u1 (lines and
// arcs run at constant speed in u, so u is the fraction of the length).
Element subElement(const Element& e, double u0, double u1);

// Streaming smoother: push elements in order, take the finished ones from the
// output vector (each push appends at most 3, finish at most 1).  Output
// elements are renumbered 1, 2, ... (objNo) in output order.
class PathSmoother {
public:
  explicit PathSmoother(const SmoothOptions& o) : opts_(o) {}
  void push(const Element& e, std::vector<Element>& out);
  // End of the input: releases the element held back for its corner.
  void finish(std::vector<Element>& out);
  bool holding() const { return held_; }
  // How many corners were smoothed (G51) and rounded (G52) so far.
  uint32_t splines() const { return splines_; }
  uint32_t arcs() const { return arcs_; }

private:
  void emit(Element e, std::vector<Element>& out);
  bool smoothCorner(const Element& next, std::vector<Element>& out);

  SmoothOptions opts_;
  bool held_ = false;
  Element hold_;              // the last tool-path element, waiting for its successor
  double holdOrigLength_ = 0; // its length before any cut (the half-length clamp)
  int32_t nextObjNo_ = 1;
  uint32_t splines_ = 0, arcs_ = 0;
};

}  // namespace stc::cnc

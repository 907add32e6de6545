// The velocity check of the path (SMC_CheckVelocities, docs/cnc.md): the end
// velocity of every element, i.e. the velocity the interpolator may keep at the
// junction with the next motion element.
//
// It works on a stream: elements are final only once the element that follows
// them is known (or the list has ended), so `checkVelocities` finalises a prefix
// of the elements not yet checked and leaves the rest for a later call.
#pragma once

#include <cstddef>
#include <span>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

struct VelocityCheckOptions {
  double angleTolDeg = 0.001;         // dAngleTol: a turn of the tangent above this (degrees) is a stop
  bool checkAddAxVelJump = false;     // bCheckAddAxVelJump
  double maxAddAxVelDifference = 0;   // dMaxAddAxVelDifference: the largest jump of an additional axis' velocity
  double dryRunVelocity = 0;          // dDryRunVelocity: > 0 caps every element's velocity
};
// TRUE if every option is finite and not negative (and the angle at most 180 degrees).
bool validOptions(const VelocityCheckOptions& o);

// TRUE for an M function or G75 element that SMC_PreAcknowledgeM has marked:
// the path runs through it.
bool passesThrough(const Element& e);
// TRUE for elements whose dynamics must be programmed (vel, acc, dec > 0): the
// motion elements (G0 included).
bool needsDynamics(const Element& e);
// The turn of the unit tangent from the end of `a` to the start of `b`, in
// degrees (0..180); -1 when either does not move X/Y/Z.
double turnAngleDeg(const Element& a, const Element& b);

// The velocity allowed at the junction of the motion elements `cur` and `next`
// (velocities already capped by the dry run): 0 when either is a G0, either does
// not move X/Y/Z, or the tangent turns by more than the tolerance; else the
// smaller velocity, capped by the additional axes' velocity jump when asked.
double junctionVelocity(const Element& cur, const Element& next, const VelocityCheckOptions& o);

struct VelocityCheckResult {
  size_t finalized = 0;   // elements at the front of `pending` that are final now
  bool error = false;     // pending[finalized] has vel, acc or dec <= 0 (SMC_CV_ACC_DEC_VEL_NONPOSITIVE)
};

// Finalises the leading elements of `pending` (the elements not yet checked, in
// queue order): caps vel by the dry run, writes velEnd and sets MarkVelChecked.
// A motion element is final once its next motion element is in `pending` (pre-
// acknowledged M functions in between are skipped), a stop element follows (M,
// dwell, G75, G92), or `endOfList`.  `cannotGrow`: the queue is full and pending[0]
// is at its front, so nothing more can arrive before it is consumed: if pending[0]
// still lacks its successor (only pre-acknowledged M functions follow it) it ends
// with 0 rather than waiting forever.
VelocityCheckResult checkVelocities(std::span<Element> pending, bool endOfList, bool cannotGrow,
                                    const VelocityCheckOptions& o);

}  // namespace stc::cnc

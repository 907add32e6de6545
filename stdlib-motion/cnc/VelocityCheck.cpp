#include "stdlib-motion/cnc/VelocityCheck.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

namespace {

constexpr double kRadToDeg = 57.295779513082320876798154814105;
// Differences of additional-axis rates below this are rounding, not a jump.
constexpr double kRateEpsilon = 1e-12;

bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }

// A stop element: the interpolator comes to rest there (M function, dwell, G75, G92).
bool isStop(const Element& e) { return !isMotion(e.type) && !passesThrough(e); }

// The additional axes' rate per path length at the end (u = 1) or start (u = 0) of
// `e`; they move linearly in u, so the rate is their change over |dP/du|.
void addAxisRates(const Element& e, double u, double (&rate)[kAxisCount]) {
  const double speed = norm(derivative(e, u));
  for (int k = AxA; k < kAxisCount; ++k) rate[k] = speed > 0 ? (e.end[k] - e.start[k]) / speed : 0;
}

}  // namespace

bool validOptions(const VelocityCheckOptions& o) {
  return std::isfinite(o.angleTolDeg) && o.angleTolDeg >= 0 && o.angleTolDeg <= 180 &&
         std::isfinite(o.maxAddAxVelDifference) && o.maxAddAxVelDifference >= 0 && std::isfinite(o.dryRunVelocity) &&
         o.dryRunVelocity >= 0;
}

bool passesThrough(const Element& e) {
  return (e.type == MoveType::MCommand || e.type == MoveType::Sync) && (e.marks & MarkMPreAcknowledged);
}

bool needsDynamics(const Element& e) { return isMotion(e.type); }

double turnAngleDeg(const Element& a, const Element& b) {
  const Vec3 t1 = endTangent(a), t2 = startTangent(b);
  if (norm(t1) == 0 || norm(t2) == 0) return -1;
  // atan2 of |sin| and cos keeps small angles exact (acos loses them near 1).
  return std::atan2(norm(cross(t1, t2)), dot(t1, t2)) * kRadToDeg;
}

double junctionVelocity(const Element& cur, const Element& next, const VelocityCheckOptions& o) {
  if (cur.type == MoveType::LinPos || next.type == MoveType::LinPos) return 0;   // G0 is positioning: stop
  const double angle = turnAngleDeg(cur, next);
  if (angle < 0 || angle > o.angleTolDeg) return 0;
  // The positions must meet too: a gap (after a dropped element) is no junction.
  const Vec3 gap = xyz(next.start) - xyz(cur.end);
  if (norm(gap) > 1e-9 * std::max(1.0, norm(xyz(cur.end)))) return 0;
  double v = std::min(cur.vel, next.vel);
  if (o.checkAddAxVelJump) {
    double r1[kAxisCount], r2[kAxisCount];
    addAxisRates(cur, 1, r1);
    addAxisRates(next, 0, r2);
    double jump = 0;
    for (int k = AxA; k < kAxisCount; ++k) jump = std::max(jump, std::fabs(r1[k] - r2[k]));
    if (jump > kRateEpsilon) v = std::min(v, o.maxAddAxVelDifference / jump);
  }
  return std::max(v, 0.0);
}

VelocityCheckResult checkVelocities(std::span<Element> pending, bool endOfList, bool cannotGrow,
                                    const VelocityCheckOptions& o) {
  VelocityCheckResult r;
  auto cap = [&](Element& e) {
    if (o.dryRunVelocity > 0 && e.vel > o.dryRunVelocity) e.vel = o.dryRunVelocity;
  };
  for (size_t i = 0; i < pending.size(); ++i) {
    Element& e = pending[i];
    if (!needsDynamics(e)) {
      // Stop and pass-through elements have no velocity of their own.
      e.velEnd = 0;
      e.marks |= MarkVelChecked;
      r.finalized = i + 1;
      continue;
    }
    if (!positiveFinite(e.vel) || !positiveFinite(e.acc) || !positiveFinite(e.dec)) {
      r.error = true;
      return r;
    }
    // The next motion element, across pre-acknowledged M functions.
    size_t j = i + 1;
    while (j < pending.size() && passesThrough(pending[j])) ++j;
    double velEnd = 0;
    if (j == pending.size()) {
      // Wait for the successor, unless the list has ended or the element is at the front of a
      // queue that cannot grow (nothing before it to consume): then it ends with a stop.
      if (!endOfList && !(cannotGrow && i == 0)) return r;
      velEnd = 0;
    } else if (isStop(pending[j])) {
      velEnd = 0;
    } else {
      Element next = pending[j];
      cap(next);
      cap(e);
      velEnd = junctionVelocity(e, next, o);
    }
    cap(e);
    e.velEnd = std::min(velEnd, e.vel);
    e.marks |= MarkVelChecked;
    r.finalized = i + 1;
  }
  return r;
}

}  // namespace stc::cnc

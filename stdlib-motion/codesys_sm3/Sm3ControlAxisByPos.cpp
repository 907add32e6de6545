// SMC_ControlAxisByPos (sm3_cnc_interpolator.st; docs/cnc.md, "SMC_ControlAxisByPos"):
// the interpolator's set position streamed into an axis as a position follow command,
// with the gap logic: a set position the axis cannot follow stops the interpolator
// (bStopIpo) while the axis catches up on a time-optimal one-axis plan.
#include <cmath>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Profiles.h"
#include "stdlib-motion/core/Trajectory.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

constexpr int16_t kGapParametersInvalid = 510;   // SMC_CAPV_GAP_VELACCDEC_INVALID (gap dynamics not usable)
constexpr int16_t kInvalidParameter = 1820;      // SMC_OS_INVALID_PARAMETER (set position NaN, infinite or beyond 1e12)

bool usable(double x, double max) { return std::isfinite(x) && x > 0 && x <= max; }

void SMC_ControlAxisByPos(sm3::SMC_ControlAxisByPos* self) {
  axisFbSlot(self, FbKind::Follow, [&](Kernel& k, FbSlot& fb, Axis& ax, const CallCtx& c) {
    const double dt = (c.intervalNs > 0 ? c.intervalNs : 1000000) * 1e-9;
    const Limits gap{self->fGapVelocity, self->fGapAcceleration, self->fGapDeceleration,
                     std::isfinite(self->fGapJerk) && self->fGapJerk >= 1e15 ? 0.0 : self->fGapJerk};
    const bool gapOk = usable(gap.vel, 1e9) && usable(gap.acc, 1e16) && usable(gap.dec, 1e16) &&
                       std::isfinite(self->fGapJerk) && self->fGapJerk > 0;
    // A set position that is not finite or beyond the position bound is never written: the axis
    // brakes as if disabled, and the error says why (kept over the follow command's outputs).
    const bool badSetPosition = self->bEnable && !bounds::position(self->fSetPosition);
    const bool want = self->bEnable && !badSetPosition;
    auto reportInput = [&] {
      if (!badSetPosition) return;
      self->bError = true;
      self->iErrorID = kInvalidParameter;
    };
    if (self->__ending) {   // braked to rest last cycle: end the command (bBusy falls)
      FollowInputs none;
      callFollow(k, fb, ax, false, false, none, c);
      if (fb.out.busy && ax.controller == &fb) k.finish(fb, &c, c.cycle, false, false, Error::None);
      self->__following = self->__braking = self->__ending = false;
    }
    if (want && !self->__following) {
      if (self->bAvoidGaps && !gapOk) {
        self->bError = true;
        self->iErrorID = kGapParametersInvalid;
        return;
      }
      const Kinematic s = ax.set();
      self->__p = s.p;
      self->__v = s.v;
      self->__a = s.a;
      self->__following = true;
      self->__catching = self->__braking = false;
      self->bError = false;
      self->iErrorID = 0;
    }
    if (!self->__following) {
      self->bStopIpo = false;
      FollowInputs none;
      callFollow(k, fb, ax, false, false, none, c);
      return reportInput();
    }
    Kinematic next{self->__p, self->__v, self->__a};
    if (!want) {
      // bEnable fell: brake with the gap deceleration, then end the command
      self->__braking = true;
      self->__catching = false;
      self->bStopIpo = false;
      // The interpolator standing (IPO_FINISHED / IPO_WAIT): the path ended at rest within the
      // last cycle, so the axis stays where it is; else brake with the gap deceleration.
      const bool pathAtRest = self->iStatus == 5 || self->iStatus == 6;
      Profile pr;
      const Limits lim{std::max(std::fabs(next.v), 1e-9), gapOk ? gap.dec : 1e15, gapOk ? gap.dec : 1e15, gap.jerk};
      if (pathAtRest) next = {next.p, 0, 0};
      else if (next.v != 0 && planVelocity(next, 0, lim, pr) == PlanStatus::Ok && pr.duration() > dt) next = pr.at(dt);
      else next = {next.p + 0.5 * next.v * std::min(dt, 1e-3), 0, 0};
    } else {
      const double target = self->fSetPosition;
      const double vmax = ax.config().maxVelocity;
      const double jump = target - next.p;
      if (!self->__catching && self->bAvoidGaps) {
        // a gap: faster than the axis may move (without a limit: a jump while it stood still)
        const bool tooFast = vmax > 0 ? std::fabs(jump) > vmax * dt * (1 + 1e-9)
                                      : (next.v == 0 && std::fabs(jump) > gap.vel * dt * (1 + 1e-9));
        if (tooFast) self->__catching = true;
      }
      if (self->__catching) {
        Profile pr;
        if (planPosition({0, next.v, next.a}, jump, 0, gap, pr) == PlanStatus::Ok && pr.duration() > dt) {
          const Kinematic q = pr.at(dt);
          next = {next.p + q.p, q.v, q.a};
        } else {
          next = {target, 0, 0};   // arrived: follow the interpolator again
          self->__catching = false;
        }
      } else {
        next = {target, (target - next.p) / dt, ((target - next.p) / dt - next.v) / dt};
      }
      self->bStopIpo = self->__catching;
    }
    self->__p = next.p;
    self->__v = next.v;
    self->__a = next.a;
    // position and velocity both given: the axis stands exactly when the stream stops
    // (an abandoned follow command keeps its last velocity)
    FollowInputs in;
    in.mask = kFollowPosition | kFollowVelocity;
    in.position = next.p;
    in.velocity = next.v;
    callFollow(k, fb, ax, true, false, in, c);
    // Stands: the step of this cycle applies the state at rest; the command ends in the next call.
    if (self->__braking && next.v == 0) self->__ending = true;
    reportInput();
  });
}

}  // namespace

namespace stc::motion::sm3face {
void registerSm3ControlAxisNatives(MotionLibrary& lib) { STC_SM3_NATIVE(SMC_ControlAxisByPos, SMC_ControlAxisByPos) }
}  // namespace stc::motion::sm3face

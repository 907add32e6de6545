// Fuzz target for the CNC path preprocessing (stdlib-motion/cnc): the decoder's elements
// go through ToolCorrector -> LoopAvoider -> PathSmoother -> checkVelocities (the chain of
// SMC_ToolCorr, SMC_AvoidLoop, SMC_SmoothPath and SMC_CheckVelocities), streamed through
// bounded queues as the SoftMotion blocks run them, and every element that leaves a stage
// is checked.  A violated invariant prints what and where and abort()s.
//   libFuzzer build: see docs/cnc.md ("Fuzzing")
// The same entry point is replayed over tests/fuzz/path_regressions by
// stc_fuzz_path_replay in the ordinary test suite.
//
// Input: four option bytes, then the program (decoded with the ordinary decoder).
//  byte 0: bits 0-1 ToolCorrMode (mod 3), bits 2-4 the default tool radius (kRadius),
//          bits 5-6 a first line "G41 D0" / "G42 D0" (D0: the default radius),
//          bit 7 decoder defaults for F / E / E- (else elements without F are an error
//          of the velocity check)
//  byte 1: bits 0-1 a second line "G51 D.." / "G52 D.." (D from kSmoothD, bits 2-4),
//          bits 5-6 dEdgeDistance (kEdge), bit 7 bSymmetricalDistances
//  byte 2: bits 0-1 the smoothing dAngleTol (kSmoothTol), bit 2 a third line "G61" (loop
//          avoidance on), bit 3 every M / G75 pre-acknowledged, bits 4-5 the velocity
//          check's dAngleTol (kCvTol), bit 6 a dry-run velocity of 10, bit 7 the additional
//          axes' velocity jump check (difference 1)
//  byte 3: bits 0-3 decoder queue capacity 4 + n, bits 4-5 the decoder's block budget per
//          step (kBudget), bits 6-7 the capacity of the velocity-checked queue (kCvCap)
//
// Invariants (docs/cnc.md, "Fuzzing"):
//  - every coordinate, centre, basis vector, radius, angle, tangent, length and velocity
//    finite; arcs with a radius > 0 whose centre / start angle / sweep / rise reproduce
//    their start and end points; length = pathLength; point(e, u) finite, point(e, 0) the
//    start; switch points well-formed;
//  - each stage's output is continuous (start of one element = end of the previous, all
//    axes, within 1e-9 x max(1, |coordinate|)) — the decoder's output is, and no stage
//    documents a gap;
//  - bounded element counts: ToolCorr emits at most 3 per input element + 1 (an inserted
//    positioning or ramp-out link, and a corner arc/link or an entry positioning, per push;
//    one positioning at finish) and holds at most kMaxLookAhead + 1 (+ 1 with the look-ahead
//    error); ToolCorr keeps every element it accepted, in order (objNo); LoopAvoider emits
//    exactly in - dropped and holds at most kWindow; PathSmoother appends at most 3 per push
//    and 2 per input element in all (the piece and one corner); the velocity check keeps
//    the count; so the end of the chain has at most 6 n + 2 elements for n decoded ones;
//  - a stage that is off (no G41/G42 with a radius > 0, no G61, no G51/G52) passes the
//    path through unchanged;
//  - errors only through the documented paths: ToolCorrector::push() false with error(),
//    a message and the line of the refused element; checkVelocities' error at an element
//    whose vel / acc / dec is not positive; never a stalled velocity check (a full queue
//    always finalises its front, the end of the list finalises everything);
//  - after the velocity check: 0 <= velEnd <= vel, MarkVelChecked, velEnd 0 at G0;
//  - LimitsCheck: elementBounds holds the start, the end and sampled points of the
//    element, and axesOutOfLimits of the element against its own bounds is 0.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <string>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/AvoidLoop.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/Geometry.h"
#include "stdlib-motion/cnc/LimitsCheck.h"
#include "stdlib-motion/cnc/SmoothPath.h"
#include "stdlib-motion/cnc/ToolCorr.h"
#include "stdlib-motion/cnc/VelocityCheck.h"

namespace {

using namespace stc;
using namespace stc::cnc;

constexpr double kRadius[8] = {0, 1e-9, 0.5, 2, 5, 1e6, 1e-3, 25};
constexpr const char* kSmoothD[8] = {"0", "0.000000001", "0.1", "1", "3", "1000000", "0.01", "10"};
constexpr double kEdge[4] = {0, 1e-9, 0.5, 1e6};
constexpr double kSmoothTol[4] = {0, 1, 45, 180};
constexpr double kCvTol[4] = {0.001, 0, 5, 180};
constexpr uint32_t kBudget[4] = {1, 3, 16, UINT32_MAX};
constexpr size_t kCvCap[4] = {2, 5, 16, 64};

// Continuity and geometric consistency, relative to the coordinates' magnitude.
constexpr double kJoinTol = 1e-9;
constexpr double kGeoTol = 1e-7;

const char* g_stage = "";
size_t g_index = 0;
const Element* g_element = nullptr;   // the element being checked, if any
const std::vector<Element>* g_before = nullptr;   // the elements of its stream before it

void dump(const Element& e) {
  std::fprintf(stderr, "  line %d type %s start", e.line, toString(e.type));
  for (double v : e.start) std::fprintf(stderr, " %.17g", v);
  std::fprintf(stderr, "\n  end");
  for (double v : e.end) std::fprintf(stderr, " %.17g", v);
  std::fprintf(stderr, "\n  length %.17g vel %g acc %g dec %g velEnd %g\n", e.length, e.vel, e.acc, e.dec, e.velEnd);
  if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
    const ArcGeo& g = e.arc;
    std::fprintf(stderr, "  arc centre %.17g %.17g %.17g radius %.17g startAngle %.17g sweep %.17g rise %.17g\n", g.centre[0],
                 g.centre[1], g.centre[2], g.radius, g.startAngle, g.sweep, g.rise);
    std::fprintf(stderr, "  u %g %g %g v %g %g %g normal %g %g %g\n", g.u[0], g.u[1], g.u[2], g.v[0], g.v[1], g.v[2],
                 g.normal[0], g.normal[1], g.normal[2]);
  }
}

[[noreturn]] void violated(const char* what) {
  std::fprintf(stderr, "path_fuzz: invariant violated after %s, element %zu: %s\n", g_stage, g_index, what);
  if (g_element) dump(*g_element);
  if (g_before && std::getenv("STC_PATH_FUZZ_VERBOSE")) {
    std::fprintf(stderr, "after:\n");
    for (size_t i = g_before->size() > 4 ? g_before->size() - 4 : 0; i < g_before->size(); ++i) dump((*g_before)[i]);
  }
  std::abort();
}
#define CHECK(cond)                   \
  do {                                \
    if (!(cond)) violated(#cond);     \
  } while (0)

bool finite(const Pos& p) {
  return std::all_of(p.begin(), p.end(), [](double v) { return std::isfinite(v); });
}
bool finite3(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
double mag(const Pos& p) {
  double m = 0;
  for (double v : p) m = std::max(m, std::fabs(v));
  return m;
}
double mag3(const Vec3& p) { return std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])}); }
bool near3(const Vec3& a, const Vec3& b, double scale) {
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(a[k] - b[k]) <= kGeoTol * scale)) return false;
  return true;
}

void checkElement(const Element& e) {
  CHECK(finite(e.start) && finite(e.end));
  CHECK(std::isfinite(e.vel) && std::isfinite(e.acc) && std::isfinite(e.dec) && std::isfinite(e.velEnd));
  CHECK(std::isfinite(e.length) && e.length >= 0);
  CHECK(std::isfinite(e.toolRadius) && std::isfinite(e.smoothDist));
  CHECK(e.switchCount <= kMaxSwitches);
  for (uint8_t i = 0; i < e.switchCount && i < kMaxSwitches; ++i) {
    CHECK(std::isfinite(e.switches[i].pos));
    if (e.switches[i].relative) CHECK(e.switches[i].pos >= 0 && e.switches[i].pos <= 1);
  }
  if (!isMotion(e.type)) return;
  const double scale = std::max({1.0, mag(e.start), mag(e.end)});
  if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
    const ArcGeo& g = e.arc;
    CHECK(finite3(g.centre) && finite3(g.u) && finite3(g.v) && finite3(g.normal));
    CHECK(std::isfinite(g.radius) && g.radius > 0 && std::isfinite(g.startAngle) && std::isfinite(g.sweep) &&
          std::isfinite(g.rise));
    CHECK((e.type == MoveType::Cclw) == (g.sweep > 0) || g.sweep == 0);
    const double s = std::max({scale, g.radius, mag3(g.centre)});
    const Vec3 a = g.centre + (g.radius * std::cos(g.startAngle)) * g.u + (g.radius * std::sin(g.startAngle)) * g.v;
    CHECK(near3(a, xyz(e.start), s));
    const double t = g.startAngle + g.sweep;
    const Vec3 b = g.centre + (g.radius * std::cos(t)) * g.u + (g.radius * std::sin(t)) * g.v + g.rise * g.normal;
    CHECK(near3(b, xyz(e.end), s));
  } else if (e.type == MoveType::Spline) {
    CHECK(finite3(e.spline.t0) && finite3(e.spline.t1) && std::isfinite(e.spline.chord));
  } else if (e.type == MoveType::Parabola) {
    CHECK(finite3(e.parabola.vertex) && finite3(e.parabola.control));
  } else if (e.type == MoveType::EllClw || e.type == MoveType::EllCclw) {
    const EllipseGeo& g = e.ellipse;
    CHECK(finite3(g.centre) && finite3(g.major) && std::isfinite(g.a) && std::isfinite(g.b) &&
          std::isfinite(g.startPhi) && std::isfinite(g.sweepPhi) && std::isfinite(g.rise));
  }
  const double L = pathLength(e);
  CHECK(std::isfinite(L) && std::fabs(L - e.length) <= 1e-6 * std::max(1.0, L));
  for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) CHECK(finite(point(e, u)));
  const Pos p0 = point(e, 0);
  for (int k = 0; k < kAxisCount; ++k) CHECK(std::fabs(p0[k] - e.start[k]) <= kGeoTol * std::max(scale, e.length));
  CHECK(point(e, 1) == e.end);
}

// The LimitsCheck core on one element: its bounds hold it, and it is inside them.
void checkLimits(const Element& e) {
  Pos lo, hi;
  elementBounds(e, lo, hi);
  if (!isMotion(e.type)) return;
  CHECK(finite(lo) && finite(hi));
  const double scale = std::max({1.0, mag(lo), mag(hi)});
  for (double u : {0.0, 0.125, 0.3, 0.5, 0.7, 0.875, 1.0}) {
    const Pos p = point(e, u);
    for (int k = 0; k < kAxisCount; ++k) CHECK(p[k] >= lo[k] - kGeoTol * scale && p[k] <= hi[k] + kGeoTol * scale);
  }
  CHECK(axesOutOfLimits(e, lo, hi, 0x7FF) == 0);
}

// The output stream of one stage: every element checked, the chain continuous.
struct Stream {
  const char* name;
  std::vector<Element> els;
  void accept(const Element& e) {
    g_stage = name;
    g_index = els.size();
    g_element = &e;
    g_before = &els;
    checkElement(e);
    if (!els.empty()) {
      const Pos& prev = els.back().end;
      for (int k = 0; k < kAxisCount; ++k) {
        const double scale = std::max({1.0, std::fabs(prev[k]), std::fabs(e.start[k])});
        CHECK(std::fabs(e.start[k] - prev[k]) <= kJoinTol * scale);
      }
    }
    g_element = nullptr;
    g_before = nullptr;
    els.push_back(e);
  }
};

bool sameGeometry(const Element& a, const Element& b) {
  return a.type == b.type && a.start == b.start && a.end == b.end && a.line == b.line;
}
void checkPassedThrough(const char* stage, const std::vector<Element>& in, const std::vector<Element>& out) {
  g_stage = stage;
  g_index = 0;
  CHECK(in.size() == out.size());
  for (size_t i = 0; i < in.size(); ++i) {
    g_index = i;
    CHECK(sameGeometry(in[i], out[i]));
  }
}

struct Options {
  ToolCorrMode mode = ToolCorrMode::BlindPos;
  double radius = 0;
  SmoothOptions smooth;
  VelocityCheckOptions cv;
  bool preAck = false;
  size_t cvCap = 2;
};

class Pipeline {
public:
  explicit Pipeline(const Options& o) : o_(o), tc_(o.mode, o.radius), sm_(o.smooth) {}

  void decoded(const Element& e) {
    dec_.accept(e);
    if (tcStopped_) return;
    if (e.toolSide != ToolSide::Off && (e.toolRadius > 0 || o_.radius > 0)) tcActive_ = true;
    const bool ok = tc_.push(e);
    ++tcIn_;
    g_stage = "ToolCorr";
    g_index = tcIn_;
    if (!ok) {
      // The documented error path: an error code, a message, the line of the refused element.
      CHECK(tc_.error() != ToolCorrError::None);
      CHECK(!tc_.errorMessage().empty());
      CHECK(tc_.errorLine() == e.line);
      CHECK(!tc_.push(e));
      tcStopped_ = true;
    } else {
      CHECK(tc_.error() == ToolCorrError::None);
    }
    // The held contour element and up to kMaxLookAhead others (one more when that is the error).
    CHECK(tc_.held() <= ToolCorrector::kMaxLookAhead + (ok ? 1 : 2));
    drainTc();
  }

  void finish() {
    if (!tcStopped_) tc_.finish();
    drainTc();
    g_stage = "ToolCorr";
    CHECK(tc_.held() == 0 || tcStopped_);
    la_.finish();
    drainLa();
    std::vector<Element> out;
    sm_.finish(out);
    g_stage = "SmoothPath";
    CHECK(out.size() <= 1);
    for (const Element& e : out) toCv(e);
    runCv(true);

    // Counts.
    g_stage = "counts";
    CHECK(tc_.stream().size() <= 3 * tcIn_ + 1);
    CHECK(la_.stream().size() + la_.dropped() == tc_.stream().size());
    CHECK(sm_.stream().size() <= 2 * la_.stream().size());
    CHECK(sm_.stream().size() <= la_.stream().size() + sm_.corners());
    if (!cvStopped_) CHECK(cv_.els.size() == sm_.stream().size());
    CHECK(cv_.els.size() <= 6 * dec_.els.size() + 2);
    // ToolCorr keeps every element it accepted (in order; inserted elements carry the number
    // of the element they belong to): no programmed element is lost.
    g_stage = "ToolCorr (elements kept)";
    for (size_t i = 1; i < tc_.stream().size(); ++i) {
      g_index = i;
      CHECK(tc_.stream()[i].objNo >= tc_.stream()[i - 1].objNo);
    }
    if (!tcStopped_) {
      size_t j = 0;
      for (size_t i = 0; i < dec_.els.size(); ++i) {
        g_index = i;
        while (j < tc_.stream().size() && tc_.stream()[j].objNo < dec_.els[i].objNo) ++j;
        CHECK(j < tc_.stream().size() && tc_.stream()[j].objNo == dec_.els[i].objNo);
      }
    }
    // Stages that are off pass the path through.
    if (!tcActive_ && !tcStopped_) checkPassedThrough("ToolCorr (off)", dec_.els, tc_.stream());
    if (!laActive_) checkPassedThrough("AvoidLoop (off)", tc_.stream(), la_.stream());
    if (!smActive_) checkPassedThrough("SmoothPath (off)", la_.stream(), sm_.stream());
  }

  // STC_PATH_FUZZ_VERBOSE: what each stage did (to check that an input reaches a stage).
  void report(unsigned decoderErrors) const {
    std::fprintf(stderr,
                 "decoded %zu (%u errors) | ToolCorr %zu%s%s | AvoidLoop %zu (%zu loops)%s | SmoothPath %zu (%u splines, "
                 "%u arcs)%s | CheckVelocities %zu%s\n",
                 dec_.els.size(), decoderErrors, tc_.stream().size(), tcActive_ ? " active" : "",
                 tcStopped_ ? (std::string(" error: ") + tc_.errorMessage()).c_str() : "", la_.stream().size(),
                 la_.la.loopsRemoved(), laActive_ ? " active" : "", sm_.stream().size(), sm_.sm.splines(), sm_.sm.arcs(),
                 smActive_ ? " active" : "", cv_.els.size(), cvStopped_ ? " error" : "");
  }

private:
  void drainTc() {
    while (tc_.hasOutput()) {
      const Element e = tc_.front();
      tc_.pop();
      tc_.out.accept(e);
      toLa(e);
    }
  }
  void toLa(const Element& e) {
    if (e.loopAvoid) laActive_ = true;
    la_.la.push(e);
    g_stage = "AvoidLoop";
    CHECK(la_.la.held() <= LoopAvoider::kWindow);
    drainLa();
  }
  void drainLa() {
    while (la_.la.hasOutput()) {
      const Element e = la_.la.front();
      la_.la.pop();
      la_.out.accept(e);
      toSm(e);
    }
  }
  void toSm(const Element& e) {
    if (e.smoothing != Smoothing::Off) smActive_ = true;
    std::vector<Element> out;
    sm_.sm.push(e, out);
    g_stage = "SmoothPath";
    CHECK(out.size() <= 3);
    for (const Element& x : out) toCv(x);
  }
  void toCv(const Element& e0) {
    sm_.out.accept(e0);
    if (cvStopped_) return;
    Element e = e0;
    if (o_.preAck && (e.type == MoveType::MCommand || e.type == MoveType::Sync)) e.marks |= MarkMPreAcknowledged;
    while (!cvStopped_ && pending_.size() >= o_.cvCap) runCv(false);
    if (cvStopped_) return;
    pending_.push_back(e);
    runCv(false);
  }
  // SMC_CheckVelocities over the queue; the consumer (the interpolator) takes the
  // finalised elements at once.
  void runCv(bool endOfList) {
    if (cvStopped_) return;
    std::vector<Element> p(pending_.begin(), pending_.end());
    const bool cannotGrow = p.size() >= o_.cvCap;
    const VelocityCheckResult r = checkVelocities(p, endOfList, cannotGrow, o_.cv);
    g_stage = "CheckVelocities";
    g_index = cv_.els.size();
    CHECK(r.finalized <= p.size());
    for (size_t i = 0; i < r.finalized; ++i) {
      const Element& e = p[i];
      cv_.accept(e);
      CHECK(e.marks & MarkVelChecked);
      CHECK(e.velEnd >= 0 && (e.velEnd <= e.vel || !needsDynamics(e)));
      if (e.type == MoveType::LinPos || !needsDynamics(e)) CHECK(e.velEnd == 0);
      if (o_.cv.dryRunVelocity > 0 && needsDynamics(e)) CHECK(e.vel <= o_.cv.dryRunVelocity);
      checkLimits(e);
      pending_.pop_front();
    }
    if (r.error) {
      CHECK(r.finalized < p.size());
      const Element& bad = p[r.finalized];
      CHECK(needsDynamics(bad) && !(bad.vel > 0 && bad.acc > 0 && bad.dec > 0 && std::isfinite(bad.vel) &&
                                    std::isfinite(bad.acc) && std::isfinite(bad.dec)));
      cvStopped_ = true;
      pending_.clear();
      return;
    }
    // Never stalled: a full queue finalises its front, the end of the list everything.
    if (cannotGrow) CHECK(r.finalized > 0);
    if (endOfList) CHECK(pending_.empty());
  }

  struct TcState {
    explicit TcState(ToolCorrMode m, double r) : tc(m, r) {}
    ToolCorrector tc;
    Stream out{"ToolCorr", {}};
    bool push(const Element& e) { return tc.push(e); }
    void finish() { tc.finish(); }
    bool hasOutput() const { return tc.hasOutput(); }
    const Element& front() const { return tc.front(); }
    void pop() { tc.pop(); }
    size_t held() const { return tc.held(); }
    ToolCorrError error() const { return tc.error(); }
    const std::string& errorMessage() const { return tc.errorMessage(); }
    int32_t errorLine() const { return tc.errorLine(); }
    const std::vector<Element>& stream() const { return out.els; }
  };
  struct LaState {
    LoopAvoider la;
    Stream out{"AvoidLoop", {}};
    void finish() { la.finish(); }
    size_t dropped() const { return la.elementsDropped(); }
    const std::vector<Element>& stream() const { return out.els; }
  };
  struct SmState {
    explicit SmState(const SmoothOptions& o) : sm(o) {}
    PathSmoother sm;
    Stream out{"SmoothPath", {}};
    void finish(std::vector<Element>& o) { sm.finish(o); }
    size_t corners() const { return sm.splines() + sm.arcs(); }
    const std::vector<Element>& stream() const { return out.els; }
  };

  Options o_;
  Stream dec_{"Decoder", {}};
  TcState tc_;
  LaState la_;
  SmState sm_;
  Stream cv_{"CheckVelocities", {}};
  std::deque<Element> pending_;
  size_t tcIn_ = 0;
  bool tcStopped_ = false, cvStopped_ = false;
  bool tcActive_ = false, laActive_ = false, smActive_ = false;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  uint8_t b[4] = {0, 0, 0, 0};
  const size_t head = std::min<size_t>(size, 4);
  for (size_t i = 0; i < head; ++i) b[i] = data[i];
  std::string text;
  if ((b[0] >> 5 & 3) == 1) text += "G41 D0\n";
  if ((b[0] >> 5 & 3) == 2) text += "G42 D0\n";
  const char* smoothD = kSmoothD[b[1] >> 2 & 7];
  if ((b[1] & 3) == 1) text += std::string("G51 D") + smoothD + "\n";
  if ((b[1] & 3) == 2) text += std::string("G52 D") + smoothD + "\n";
  if (b[2] & 4) text += "G61\n";
  text.append(reinterpret_cast<const char*>(data) + head, size - head);

  Options o;
  o.mode = static_cast<ToolCorrMode>((b[0] & 3) % 3);
  o.radius = kRadius[b[0] >> 2 & 7];
  o.smooth.edgeDistance = kEdge[b[1] >> 5 & 3];
  o.smooth.symmetric = b[1] & 128;
  o.smooth.angleTolDeg = kSmoothTol[b[2] & 3];
  o.preAck = b[2] & 8;
  o.cv.angleTolDeg = kCvTol[b[2] >> 4 & 3];
  o.cv.dryRunVelocity = (b[2] & 64) ? 10 : 0;
  o.cv.checkAddAxVelJump = b[2] & 128;
  o.cv.maxAddAxVelDifference = (b[2] & 128) ? 1 : 0;
  o.cvCap = kCvCap[b[3] >> 6 & 3];

  SourceManager sm;
  DiagnosticsEngine diags(sm);
  const uint32_t file = sm.addBuffer("fuzz.cnc", text);
  DecoderOptions d;
  if (b[0] & 128) d.defaultVel = 100, d.defaultAcc = 1000, d.defaultDec = 1000;
  d.maxJumps = 50;
  Decoder dec(sm, file, diags, d);
  ElementQueue q(4 + (b[3] & 15));
  const uint32_t budget = kBudget[b[3] >> 4 & 3];
  Pipeline p(o);
  for (int calls = 0;; ++calls) {
    if (calls > 10000000) violated("the decoder does not finish");
    const StepResult r = dec.step(q, budget);
    while (!q.empty()) {
      p.decoded(q.front());
      q.pop();
    }
    if (r.status == StepStatus::Finished) break;
  }
  p.finish();
  static const bool verbose = std::getenv("STC_PATH_FUZZ_VERBOSE") != nullptr;
  if (verbose) p.report(dec.errorCount());
  return 0;
}

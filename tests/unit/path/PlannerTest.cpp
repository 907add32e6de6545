// Path planner (stdlib-motion/path/Planner.h) cycle by cycle at dt = 1 ms:
// closed forms, blends, limits, look-ahead, override/hold/halt/abort, and
// 1,000 random segment sequences.
#include "stdlib-motion/path/Planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

using namespace stc::motion::path;

namespace {

constexpr double kDt = 0.001;
constexpr double kPi = std::numbers::pi;

Vec V(double x, double y, double z = 0) {
  Vec v{};
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}
double dist(const Vec& a, const Vec& b, int n = 3) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

MoveSpec line(const Vec& end, Dynamics d, BufferMode b = BufferMode::Buffered, TransitionMode t = TransitionMode::None,
              double tp = 0) {
  MoveSpec m;
  m.kind = MoveKind::Line;
  m.end = end;
  m.dyn = d;
  m.buffer = b;
  m.transition = t;
  m.transitionParam = tp;
  return m;
}

struct Trace {
  std::vector<Sample> s;
  std::vector<std::pair<int, Event>> ev;   // (cycle, event)
};

// Runs until idle (or maxCycles); records every sample and event.
Trace runToEnd(Planner& p, int maxCycles = 200000) {
  Trace r;
  for (int i = 0; i < maxCycles && !p.idle(); ++i) {
    r.s.push_back(p.advance(kDt));
    for (const Event& e : p.events()) r.ev.push_back({i, e});
    p.clearEvents();
  }
  return r;
}

TEST(PathPlanner, LinearMoveStaysOnTheLineAndTakesTheTrapezoidTime) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  const auto r = p.append(line(V(30, 40), {10, 100, 100, 0}));
  ASSERT_EQ(r.status, PathStatus::Ok);
  ASSERT_EQ(p.events().size(), 1u);
  EXPECT_EQ(p.events()[0].kind, EventKind::Started);
  p.clearEvents();
  Trace run = runToEnd(p);
  // 50 units at v = 10, a = d = 100: 5 s cruise-equivalent + 0.1 s ramps
  ASSERT_EQ(run.s.size(), 5100u);
  double doneT = -1;
  for (auto& [c, e] : run.ev)
    if (e.kind == EventKind::Done) doneT = c * kDt + e.t;
  EXPECT_NEAR(doneT, 5.1, 1e-9);
  for (const Sample& s : run.s) {
    EXPECT_NEAR(s.pos[0] * 0.8 - s.pos[1] * 0.6, 0.0, 1e-9);   // on the line
    EXPECT_LE(s.v, 10 + 1e-9);
  }
  EXPECT_EQ(run.s.back().pos, V(30, 40));
  EXPECT_EQ(p.planFailures(), 0u);
}

TEST(PathPlanner, FullCircleKeepsItsRadiusAndEndsAtTheStart) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  p.setPosition(V(10, 0));
  MoveSpec m;
  m.kind = MoveKind::ArcCenter;
  m.aux = V(0, 0);
  m.end = V(10, 0);
  m.dyn = {20, 200, 200, 2000};
  ASSERT_EQ(p.append(m).status, PathStatus::Ok);
  Trace run = runToEnd(p);
  double maxA = 0;
  for (const Sample& s : run.s) {
    EXPECT_NEAR(std::hypot(s.pos[0], s.pos[1]), 10, 1e-9);
    maxA = std::max(maxA, std::hypot(s.acc[0], s.acc[1]));
  }
  EXPECT_EQ(run.s.back().pos, V(10, 0));
  // centripetal limit: v^2 / r <= Acceleration, so v <= sqrt(200 * 10) ~ 44.7: the feed 20 holds
  EXPECT_LE(maxA, std::hypot(200, 20.0 * 20 / 10) + 1e-6);
  // T = L / v + v / a + a / j (two jerk-limited ramps)
  EXPECT_NEAR(run.s.size() * kDt, 2 * kPi * 10 / 20 + 20.0 / 200 + 200.0 / 2000, 0.0015);
}

TEST(PathPlanner, CentripetalLimitLowersTheFeedOnTightArcs) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  p.setPosition(V(1, 0));
  MoveSpec m;
  m.kind = MoveKind::ArcCenter;
  m.aux = V(0, 0);
  m.end = V(1, 0);
  m.turns = 3;
  m.dyn = {100, 100, 100, 0};   // v^2 / r <= 100 -> v <= 10
  ASSERT_EQ(p.append(m).status, PathStatus::Ok);
  Trace run = runToEnd(p);
  double vmax = 0;
  for (const Sample& s : run.s) vmax = std::max(vmax, s.v);
  EXPECT_NEAR(vmax, 10, 1e-9);
}

// Two lines with a corner of 90 degrees blended at distance d.
TEST(PathPlanner, BlendedCornerStaysInsideAndKeepsTheBlendVelocity) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  const Dynamics dyn{10, 50, 50, 0};
  ASSERT_EQ(p.append(line(V(20, 0), dyn, BufferMode::Aborting)).status, PathStatus::Ok);
  const double d = 2;
  const auto r = p.append(line(V(20, 20), dyn, BufferMode::BlendingNext, TransitionMode::CornerDistance, d));
  ASSERT_EQ(r.status, PathStatus::Ok);
  EXPECT_FALSE(r.blendDropped);
  p.clearEvents();
  // independent: the blend's peak curvature, densely sampled
  Segment A, B, bl;
  Segment::line(V(0, 0), V(20, 0), 2, A);
  Segment::line(V(20, 0), V(20, 20), 2, B);
  blendBetween(A, 20 - d, B, d, bl);
  double kmax = 0;
  for (int i = 0; i <= 20000; ++i) {
    PathPoint pp;
    bl.eval(bl.length() * i / 20000, pp);
    kmax = std::max(kmax, pp.curvature);
  }
  const double vBlend = std::min(10.0, std::sqrt(50 / kmax));
  Trace run = runToEnd(p);
  double vMinInBlend = 1e9;
  int inBlend = 0;
  for (const Sample& s : run.s) {
    const bool onA = std::fabs(s.pos[1]) < 1e-12 && s.pos[0] <= 20 - d + 1e-9;
    const bool onB = std::fabs(s.pos[0] - 20) < 1e-12 && s.pos[1] >= d - 1e-9;
    if (!onA && !onB) {
      ++inBlend;
      EXPECT_LE(dist(s.pos, V(20, 0), 2), d + 1e-9);
      vMinInBlend = std::min(vMinInBlend, s.v);
    }
  }
  EXPECT_GT(inBlend, 100);
  EXPECT_GE(vMinInBlend, vBlend * (1 - 1e-8));
  EXPECT_LT(vMinInBlend, vBlend * 1.01);   // it does slow down to it
  // the moves: 1 done when the blend starts, 2 started at the same instant
  ASSERT_GE(run.ev.size(), 3u);
  EXPECT_EQ(run.ev[0].second.kind, EventKind::Done);
  EXPECT_EQ(run.ev[0].second.id, 1u);
  EXPECT_EQ(run.ev[1].second.kind, EventKind::Started);
  EXPECT_EQ(run.ev[1].second.id, 2u);
  EXPECT_EQ(run.ev[0].first, run.ev[1].first);
  EXPECT_EQ(run.ev[0].second.t, run.ev[1].second.t);
  EXPECT_EQ(run.s.back().pos, V(20, 20));
}

TEST(PathPlanner, BufferedCornerStopsExactly) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  const Dynamics dyn{10, 100, 100, 0};
  p.append(line(V(10, 0), dyn));
  p.append(line(V(10, 10), dyn));
  p.clearEvents();
  Trace run = runToEnd(p);
  // the corner is reached at v = 0: closed form 1 s + 0.1 s per line
  double done1 = -1, start2 = -1;
  for (auto& [c, e] : run.ev) {
    if (e.id == 1 && e.kind == EventKind::Done) done1 = c * kDt + e.t;
    if (e.id == 2 && e.kind == EventKind::Started) start2 = c * kDt + e.t;
  }
  EXPECT_NEAR(done1, 1.1, 1e-8);
  EXPECT_EQ(done1, start2);
  EXPECT_NEAR(run.s.size() * kDt, 2.2, 1e-8 + kDt);
  for (const Sample& s : run.s) EXPECT_TRUE(std::fabs(s.pos[1]) < 1e-12 || std::fabs(s.pos[0] - 10) < 1e-12);
}

TEST(PathPlanner, ErrorsOfTheManual) {
  PlannerConfig cfg;
  cfg.dims = 2;
  cfg.capacity = 4;
  Planner p(cfg);
  const Dynamics dyn{10, 100, 100, 0};
  EXPECT_EQ(p.append(line(V(1, 0), dyn, BufferMode::BlendingLow)).status, PathStatus::BlendingNeedsTransition);
  EXPECT_EQ(p.append(line(V(1, 0), dyn, BufferMode::Buffered, TransitionMode::CornerDistance, 1)).status,
            PathStatus::TransitionNotAllowed);
  EXPECT_EQ(p.append(line(V(1, 0), {std::nan(""), 1, 1, 0})).status, PathStatus::InvalidDynamics);
  EXPECT_EQ(p.append(line(V(1, 0), {1, 0, 1, 0})).status, PathStatus::InvalidDynamics);
  EXPECT_EQ(p.append(line(V(1, 0), {1, 1, 1, -1})).status, PathStatus::InvalidDynamics);
  const auto r = p.append(line(V(0, 0), dyn));
  EXPECT_EQ(r.status, PathStatus::InvalidGeometry);
  EXPECT_EQ(r.geo, GeoStatus::ZeroLength);
  EXPECT_EQ(p.append(line(V(1, std::numeric_limits<double>::infinity()), dyn)).status, PathStatus::InvalidGeometry);
  EXPECT_EQ(p.append(line(V(1, 0), dyn, BufferMode::BlendingLow, TransitionMode::CornerDistance, -1)).status,
            PathStatus::InvalidTransitionParameter);
  EXPECT_TRUE(p.idle());
  int ok = 0;
  for (int i = 0; i < 10; ++i) ok += p.append(line(V(i + 1, 0), dyn)).status == PathStatus::Ok;
  EXPECT_EQ(ok, 3);   // capacity 4: room for one more segment (a blend) is kept
  EXPECT_EQ(p.append(line(V(50, 0), dyn)).status, PathStatus::QueueFull);
  EXPECT_EQ(p.setOverride(-1), PathStatus::InvalidOverride);
  EXPECT_EQ(p.resume(), PathStatus::NotHeld);
}

TEST(PathPlanner, AxisLimitsHoldOnEverySample) {
  PlannerConfig cfg;
  cfg.dims = 3;
  cfg.axes.count = 3;
  const double vl[3] = {6, 4, 8}, al[3] = {40, 30, 60};
  for (int i = 0; i < 3; ++i) cfg.axes.vel[i] = vl[i], cfg.axes.acc[i] = al[i];
  Planner p(cfg);
  const Dynamics dyn{20, 200, 200, 0};
  p.append(line(V(20, 10, 5), dyn, BufferMode::Aborting));
  MoveSpec arc;
  arc.kind = MoveKind::ArcBorder;
  arc.aux = V(25, 15, 5);
  arc.end = V(20, 20, 5);
  arc.dyn = dyn;
  arc.buffer = BufferMode::BlendingHigh;
  arc.transition = TransitionMode::CornerDistance;
  arc.transitionParam = 1.5;
  ASSERT_EQ(p.append(arc).status, PathStatus::Ok);
  p.append(line(V(0, 0, 0), dyn, BufferMode::BlendingLow, TransitionMode::CornerDistance, 3));
  Trace run = runToEnd(p);
  for (size_t k = 1; k + 1 < run.s.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const double v = (run.s[k + 1].pos[i] - run.s[k - 1].pos[i]) / (2 * kDt);
      const double a = (run.s[k + 1].pos[i] - 2 * run.s[k].pos[i] + run.s[k - 1].pos[i]) / (kDt * kDt);
      EXPECT_LE(std::fabs(v), vl[i] * (1 + 1e-6)) << "axis " << i << " cycle " << k;
      EXPECT_LE(std::fabs(a), al[i] * (1 + 1e-3) + 1e-6) << "axis " << i << " cycle " << k;
      EXPECT_LE(std::fabs(run.s[k].vel[i]), vl[i] * (1 + 1e-9));
    }
  }
  EXPECT_EQ(run.s.back().pos, V(0, 0, 0));
}

TEST(PathPlanner, ManyShortBlendedSegmentsKeepTheFeed) {
  PlannerConfig cfg;
  cfg.dims = 2;
  cfg.capacity = 64;
  Planner p(cfg);
  const Dynamics dyn{50, 500, 500, 5000};
  // a gentle zigzag of 400 segments of length ~1, appended as the queue drains
  int next = 0;
  auto feed = [&] {
    while (next < 400 && p.queued() < cfg.capacity - 4) {
      const Vec e = V(next + 1.0, (next % 2) ? 0.0 : 0.05);
      ASSERT_EQ(p.append(line(e, dyn, next == 0 ? BufferMode::Aborting : BufferMode::BlendingNext,
                              next == 0 ? TransitionMode::None : TransitionMode::CornerDistance, 0.3))
                    .status,
                PathStatus::Ok);
      ++next;
    }
  };
  feed();
  std::vector<double> v;
  Vec last = p.sample().pos;
  for (int i = 0; i < 100000 && !p.idle(); ++i) {
    const Sample& s = p.advance(kDt);
    EXPECT_LE(dist(s.pos, last, 2), 50 * kDt * (1 + 1e-9) + 1e-12);
    last = s.pos;
    v.push_back(s.v);
    p.clearEvents();
    feed();
  }
  ASSERT_GT(v.size(), 1000u);
  // after the start ramp and before the final stop the feed stays near 50
  const size_t a = v.size() / 4, b = 3 * v.size() / 4;
  const double vmin = *std::min_element(v.begin() + a, v.begin() + b);
  EXPECT_GT(vmin, 40.0);
  EXPECT_NEAR(last[0], 400, 1e-9);
  // bounded work: replans and backward-pass steps per segment appended
  EXPECT_LT(p.replans(), 6u * 800);
  EXPECT_LT(p.backwardSteps(), 20u * 800);
  EXPECT_EQ(p.planFailures(), 0u);
}

TEST(PathPlanner, OverrideAndHoldStayOnThePath) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  p.setPosition(V(10, 0));
  MoveSpec m;
  m.kind = MoveKind::ArcCenter;
  m.aux = V(0, 0);
  m.end = V(-10, 0);
  m.dyn = {10, 100, 100, 1000};
  p.append(m);
  int cycles = 0;
  double vmax = 0;
  while (!p.idle() && cycles < 100000) {
    if (cycles == 500) p.setOverride(0.5);
    if (cycles == 1000) p.setOverride(0);
    if (cycles == 1200) p.setOverride(1);
    const Vec before = p.sample().pos;
    const Sample& s = p.advance(kDt);
    EXPECT_NEAR(std::hypot(s.pos[0], s.pos[1]), 10, 1e-9);
    if (cycles >= 1000 && cycles < 1200) {
      EXPECT_EQ(s.pos, before);
      EXPECT_EQ(s.v, 0);
    }
    if (cycles > 520 && cycles < 1000) vmax = std::max(vmax, s.v);
    ++cycles;
  }
  EXPECT_NEAR(vmax, 5, 1e-9);
  EXPECT_NEAR(p.sample().pos[0], -10, 1e-12);
}

TEST(PathPlanner, HaltStopsOnThePathAndAbortsTheQueue) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  p.setPosition(V(10, 0));
  MoveSpec m;
  m.kind = MoveKind::ArcCenter;
  m.aux = V(0, 0);
  m.end = V(10, 0);
  m.dyn = {10, 100, 100, 1000};
  const uint32_t id1 = p.append(m).id;
  const uint32_t id2 = p.append(line(V(20, 0), {10, 100, 100, 0})).id;
  for (int i = 0; i < 1000; ++i) p.advance(kDt);
  p.clearEvents();
  const uint32_t h = p.halt(200, 4000);   // above the move's own (the larger of both is used)
  ASSERT_EQ(p.events().size(), 3u);
  EXPECT_EQ(p.events()[0].id, id1);
  EXPECT_EQ(p.events()[0].kind, EventKind::Aborted);
  EXPECT_EQ(p.events()[1].id, id2);
  EXPECT_EQ(p.events()[1].kind, EventKind::Aborted);
  EXPECT_EQ(p.events()[2].id, h);
  p.clearEvents();
  double prevV = p.sample().v;
  Trace run = runToEnd(p);
  for (const Sample& s : run.s) {
    EXPECT_NEAR(std::hypot(s.pos[0], s.pos[1]), 10, 1e-9);
    EXPECT_LE(s.v, prevV + 1e-9);
    prevV = s.v;
  }
  ASSERT_EQ(run.ev.size(), 1u);
  EXPECT_EQ(run.ev[0].second.id, h);
  EXPECT_EQ(run.ev[0].second.kind, EventKind::Done);
  // braking from 10 at 200 u/s^2 with jerk 4000: 10 / 200 + 200 / 4000 = 0.1 s
  EXPECT_NEAR(run.s.size() * kDt, 0.1, 0.0015);
}

TEST(PathPlanner, InterruptAndResumeContinueThePath) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  const Dynamics dyn{10, 100, 100, 0};
  p.append(line(V(30, 40), dyn));
  for (int i = 0; i < 1000; ++i) p.advance(kDt);
  ASSERT_EQ(p.interrupt(100, 0), PathStatus::Ok);
  Vec last = p.sample().pos;
  for (int i = 0; i < 500; ++i) {
    const Sample& s = p.advance(kDt);
    EXPECT_NEAR(s.pos[0] * 0.8 - s.pos[1] * 0.6, 0.0, 1e-9);
    last = s.pos;
  }
  EXPECT_TRUE(p.sample().held);
  EXPECT_EQ(p.sample().v, 0);
  EXPECT_NEAR(dist(last, V(0, 0), 2), 0.5 + 9.0 + 0.5, 1e-9);   // ramp 0.1 s (0.5) + cruise 0.9 s + stop at 100 u/s^2 (0.5)
  ASSERT_EQ(p.resume(), PathStatus::Ok);
  Trace run = runToEnd(p);
  for (const Sample& s : run.s) EXPECT_NEAR(s.pos[0] * 0.8 - s.pos[1] * 0.6, 0.0, 1e-9);
  EXPECT_EQ(run.s.back().pos, V(30, 40));
}

TEST(PathPlanner, AbortingMoveStopsOnThePathThenStarts) {
  PlannerConfig cfg;
  cfg.dims = 2;
  Planner p(cfg);
  const Dynamics dyn{10, 100, 100, 1000};
  const uint32_t id1 = p.append(line(V(100, 0), dyn)).id;
  for (int i = 0; i < 1000; ++i) p.advance(kDt);
  p.clearEvents();
  const auto r = p.append(line(V(0, 50), dyn, BufferMode::Aborting));
  ASSERT_EQ(r.status, PathStatus::Ok);
  ASSERT_EQ(p.events().size(), 2u);
  EXPECT_EQ(p.events()[0].id, id1);
  EXPECT_EQ(p.events()[0].kind, EventKind::Aborted);
  EXPECT_EQ(p.events()[1].id, r.id);
  EXPECT_EQ(p.events()[1].kind, EventKind::Started);
  p.clearEvents();
  Vec last = p.sample().pos;
  Trace run = runToEnd(p);
  for (const Sample& s : run.s) {
    EXPECT_LE(dist(s.pos, last, 2), 10 * kDt + 1e-12);
    last = s.pos;
    if (s.moving) {
      EXPECT_EQ(s.active, r.id);
    }
  }
  EXPECT_EQ(run.s.back().pos, V(0, 50));
  ASSERT_EQ(run.ev.size(), 1u);
  EXPECT_EQ(run.ev[0].second.kind, EventKind::Done);
}

TEST(PathPlanner, EllipseSplineAndHelixMovesRunOnTheirGeometry) {
  PlannerConfig cfg;
  cfg.dims = 3;
  Planner p(cfg);
  p.setPosition(V(10, 0, 0));
  MoveSpec e;
  e.kind = MoveKind::Ellipse;
  e.aux = V(0, 0, 0);
  e.end = V(-10, 0, 0);
  e.ratio = 0.5;
  e.dyn = {20, 200, 200, 2000};
  ASSERT_EQ(p.append(e).status, PathStatus::Ok);
  MoveSpec h;
  h.kind = MoveKind::ArcCenter;
  h.aux = V(0, 0, 0);
  h.end = V(-10, 0, 5);
  h.turns = 1;
  h.dyn = e.dyn;
  ASSERT_EQ(p.append(h).status, PathStatus::Ok);
  std::vector<Vec> pts = {V(-5, 5, 6), V(0, 0, 7), V(5, 5, 8)};
  MoveSpec sp;
  sp.kind = MoveKind::Spline;
  sp.points = pts;
  sp.dyn = e.dyn;
  ASSERT_EQ(p.append(sp).status, PathStatus::Ok);
  Trace run = runToEnd(p);
  Vec last = V(10, 0, 0);
  for (const Sample& s : run.s) {
    EXPECT_LE(dist(s.pos, last), 20 * kDt * (1 + 1e-9) + 1e-12);
    last = s.pos;
    if (s.active == 1) {
      EXPECT_NEAR(s.pos[0] * s.pos[0] / 100 + s.pos[1] * s.pos[1] / 25, 1, 1e-9);
    }
    if (s.active == 2) {
      EXPECT_NEAR(std::hypot(s.pos[0], s.pos[1]), 10, 1e-9);
    }
  }
  EXPECT_EQ(run.s.back().pos, V(5, 5, 8));
}

// 1,000 random sequences of lines and arcs with random buffer/transition modes.
TEST(PathPlanner, RandomSequencesAreContinuousWithinLimitsAndEndAtTheTarget) {
  std::mt19937_64 g(20240615);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); };
  int blends = 0, dropped = 0;
  for (int seq = 0; seq < 1000; ++seq) {
    PlannerConfig cfg;
    cfg.dims = 3;
    cfg.capacity = 32;
    cfg.axes.count = 3;
    for (int i = 0; i < 3; ++i) cfg.axes.vel[i] = uni(20, 60), cfg.axes.acc[i] = uni(300, 1500);
    Planner p(cfg);
    Vec cur = V(0, 0, 0);
    const int n = 2 + static_cast<int>(g() % 5);
    double vmax = 0;
    std::vector<uint32_t> ids;
    for (int k = 0; k < n; ++k) {
      MoveSpec m;
      m.dyn = {uni(5, 50), uni(100, 1000), uni(100, 1000), (g() % 2) ? 0.0 : uni(1000, 20000)};
      vmax = std::max(vmax, m.dyn.vel);
      const int mode = static_cast<int>(g() % 4);
      m.buffer = k == 0 ? BufferMode::Aborting : mode == 0 ? BufferMode::Buffered : static_cast<BufferMode>(1 + mode);
      if (m.buffer >= BufferMode::BlendingLow) {
        m.transition = TransitionMode::CornerDistance;
        m.transitionParam = uni(0.1, 5);
      }
      Vec end = V(cur[0] + uni(-20, 20), cur[1] + uni(-20, 20), cur[2] + uni(-5, 5));
      if (g() % 3 == 0) {
        m.kind = MoveKind::ArcBorder;
        // a border point off the chord
        m.aux = V(0.5 * (cur[0] + end[0]) + uni(-8, 8), 0.5 * (cur[1] + end[1]) + uni(-8, 8), 0.5 * (cur[2] + end[2]));
      } else {
        m.kind = MoveKind::Line;
      }
      m.end = end;
      const auto r = p.append(m);
      if (r.status != PathStatus::Ok) continue;   // e.g. a degenerate random arc
      ids.push_back(r.id);
      cur = end;
      blends += m.buffer >= BufferMode::BlendingLow;
      dropped += r.blendDropped;
      // sometimes run a little before appending the next
      for (int i = static_cast<int>(g() % 300); i > 0; --i) p.advance(kDt);
    }
    p.clearEvents();
    Vec last = p.sample().pos;
    Vec lastV = p.sample().vel;
    for (int i = 0; i < 400000 && !p.idle(); ++i) {
      const Sample& s = p.advance(kDt);
      ASSERT_LE(dist(s.pos, last), vmax * kDt * (1 + 1e-9) + 1e-9) << "seq " << seq << " cycle " << i;
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(std::fabs(s.vel[a]), cfg.axes.vel[a] * (1 + 1e-6)) << "seq " << seq;
        ASSERT_LE(std::fabs(s.vel[a] - lastV[a]) / kDt, cfg.axes.acc[a] * 1.05 + 1e-6) << "seq " << seq << " axis " << a << " cycle " << i;
      }
      last = s.pos;
      lastV = s.vel;
      ASSERT_FALSE(std::isnan(s.pos[0] + s.pos[1] + s.pos[2]));
    }
    ASSERT_TRUE(p.idle()) << "seq " << seq;
    ASSERT_EQ(p.sample().pos, cur) << "seq " << seq;
    ASSERT_EQ(p.planFailures(), 0u) << "seq " << seq;
  }
  EXPECT_GT(blends, 1000);
  EXPECT_LT(dropped, blends / 4);
}

}  // namespace

// A move appended after the planner ran dry (no setPosition in between) runs its full
// trapezoid from the end point, and a Buffered move with a junction velocity passes the
// (collinear) junction at that velocity instead of stopping.
TEST(PathPlanner, AppendAfterRunningDryAndJunctionVelocity) {
  PlannerConfig cfg;
  cfg.dims = 3;
  Planner p(cfg);
  Vec b{};
  b[0] = 10;
  MoveSpec m;
  m.kind = MoveKind::Line;
  m.end = b;
  m.buffer = BufferMode::Buffered;
  m.dyn = {10, 100, 100, 0};
  ASSERT_EQ(p.append(m).status, PathStatus::Ok);
  for (int i = 0; i < 1100; ++i) p.advance(0.001);
  ASSERT_TRUE(p.idle());
  EXPECT_EQ(p.sample().pos[0], 10.0);
  Vec c = b;
  c[1] = 10;
  m.end = c;
  ASSERT_EQ(p.append(m).status, PathStatus::Ok);
  EXPECT_NEAR(p.remaining(), 10.0, 1e-12);
  EXPECT_NEAR(p.advance(0.001).pos[1], 0.5 * 100 * 1e-6, 1e-12);
  int n = 1;
  while (!p.idle() && n < 5000) p.advance(0.001), ++n;
  EXPECT_EQ(n, 1100);
  // collinear continuation with junction velocity 5: no stop at X = 20
  Planner q(cfg);
  m.end = {10, 0, 0};
  ASSERT_EQ(q.append(m).status, PathStatus::Ok);
  m.end = {20, 0, 0};
  m.junctionVel = 5;
  ASSERT_EQ(q.append(m).status, PathStatus::Ok);
  double minV = 1e9;
  while (!q.idle()) {
    const Sample& s = q.advance(0.001);
    if (s.pos[0] > 9 && s.pos[0] < 11) minV = std::min(minV, s.v);
  }
  EXPECT_NEAR(minV, 5.0, 0.2);
}

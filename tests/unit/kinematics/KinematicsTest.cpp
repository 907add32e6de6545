// The kinematics library: closed forms per model, 100,000 seeded random round
// trips per model (joints -> pose -> joints in the same configuration, to
// 1e-12), analytic Jacobians against central differences, and the status of
// unreachable, singular and invalid inputs (never NaN).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include "stdlib-motion/kinematics/Articulated.h"
#include "stdlib-motion/kinematics/Cartesian.h"
#include "stdlib-motion/kinematics/Delta.h"
#include "stdlib-motion/kinematics/Scara.h"
#include "stdlib-motion/kinematics/Stewart.h"

using namespace stc::motion::kin;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;
constexpr int kSamples = 100000;

unsigned seed() {
  const char* s = std::getenv("STC_KIN_SEED");
  return s ? static_cast<unsigned>(std::strtoul(s, nullptr, 10)) : 20240615u;
}

Pose poseAt(double x, double y, double z, double phi = 0) {
  Pose p;
  p.p = {x, y, z};
  p.R = rotZ(phi);
  return p;
}

double poseError(const Pose& a, const Pose& b) {
  return std::max((a.p - b.p).cwiseAbs().maxCoeff(), (a.R - b.R).cwiseAbs().maxCoeff());
}

// One random round trip: q -> forward -> inverse(configOf(q), qNear = q) -> q'.
// `lengthScale` scales the tolerance of prismatic joints and positions.
struct RoundTripStats {
  double maxJointErr = 0, maxPoseErr = 0, maxJacErr = 0;
  int count = 0;
};

void roundTrip(const Kinematics& k, const double* q, double lengthScale, RoundTripStats& st, bool jac,
               const char* what) {
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok) << what;
  const Config c = k.configOf(q);
  double q2[kMaxJoints];
  ASSERT_EQ(k.inverse(x, c, q, q2), KinStatus::Ok) << what;
  for (int i = 0; i < k.joints(); ++i) {
    const double tol = k.revolute(i) ? 1.0 : lengthScale;
    st.maxJointErr = std::max(st.maxJointErr, std::abs(q2[i] - q[i]) / tol);
  }
  Pose x2;
  ASSERT_EQ(k.forward(q2, x2), KinStatus::Ok) << what;
  st.maxPoseErr = std::max(st.maxPoseErr, std::max((x.p - x2.p).cwiseAbs().maxCoeff() / lengthScale,
                                                   (x.R - x2.R).cwiseAbs().maxCoeff()));
  EXPECT_EQ(k.configOf(q2), c) << what;
  if (jac) {
    Jacobian J, N;
    k.jacobian(q, J);
    k.numericJacobian(q, N, 1e-6);
    const double scale = 1 + J.cwiseAbs().maxCoeff();
    st.maxJacErr = std::max(st.maxJacErr, (J - N).cwiseAbs().maxCoeff() / scale);
  }
  ++st.count;
}

void expectStats(const RoundTripStats& st, const char* what) {
  EXPECT_EQ(st.count, kSamples) << what;
  EXPECT_LE(st.maxJointErr, 1e-12) << what;
  EXPECT_LE(st.maxPoseErr, 1e-12) << what;
  EXPECT_LE(st.maxJacErr, 1e-6) << what;
  std::printf("[ stats    ] %-20s %d samples: joints %.2e, pose %.2e, Jacobian %.2e\n", what, st.count, st.maxJointErr,
              st.maxPoseErr, st.maxJacErr);
}

// Garbage poses: the status is Ok/Singular with finite joints, or the joints are untouched.
void neverNaN(const Kinematics& k, const char* what) {
  std::mt19937_64 rng(seed() + 7);
  std::uniform_real_distribution<double> u(-1, 1);
  const double specials[] = {0.0, 1e-300, 1e300, -1e300, std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN(), 1e6, -1e6};
  for (int n = 0; n < 2000; ++n) {
    Pose x;
    for (int i = 0; i < 3; ++i) x.p[i] = n % 4 == 0 ? specials[rng() % 8] : u(rng) * std::pow(10.0, u(rng) * 4);
    x.R = Eigen::AngleAxisd(u(rng) * kPi, Eigen::Vector3d(u(rng), u(rng), u(rng) + 1e-3).normalized()).toRotationMatrix();
    if (n % 17 == 0) x.R(1, 1) = specials[rng() % 8];
    double q[kMaxJoints], q0[kMaxJoints];
    for (int i = 0; i < kMaxJoints; ++i) q[i] = q0[i] = 12345.0;
    const Config c{static_cast<int8_t>(rng() % 2 ? 1 : -1), static_cast<int8_t>(rng() % 2 ? 1 : -1),
                   static_cast<int8_t>(rng() % 2 ? 1 : -1)};
    const KinStatus s = k.inverse(x, c, n % 3 ? q0 : nullptr, q);
    if (s == KinStatus::Ok || s == KinStatus::Singular) {
      for (int i = 0; i < k.joints(); ++i) ASSERT_TRUE(std::isfinite(q[i])) << what;
    } else {
      for (int i = 0; i < k.joints(); ++i) ASSERT_EQ(q[i], 12345.0) << what;
    }
    // Joints: forward and Jacobian never produce NaN either.
    double qj[kMaxJoints];
    for (int i = 0; i < kMaxJoints; ++i) qj[i] = n % 5 == 0 ? specials[rng() % 8] : u(rng) * 10;
    Pose y;
    const KinStatus sf = k.forward(qj, y);
    if (sf == KinStatus::Ok || sf == KinStatus::Singular) {
      ASSERT_TRUE(finite(y)) << what;
    }
    Jacobian J;
    k.jacobian(qj, J);
    ASSERT_TRUE(J.allFinite()) << what;
  }
}

// ---------------------------------------------------------------- Cartesian / gantry
TEST(KinCartesian, IdentityAndEulerAngles) {
  Cartesian k(6);
  const double q[6] = {1, 2, 3, 0.3, -0.2, 0.1};
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok);
  EXPECT_EQ(x.p, Eigen::Vector3d(1, 2, 3));
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX())).toRotationMatrix();
  EXPECT_LT((x.R - R).norm(), 1e-15);
  Cartesian k2(2);
  const double q2[2] = {4, 5};
  ASSERT_EQ(k2.forward(q2, x), KinStatus::Ok);
  EXPECT_EQ(x.p, Eigen::Vector3d(4, 5, 0));
  EXPECT_FALSE(Cartesian(0).valid());
  EXPECT_FALSE(Cartesian(7).valid());
}

TEST(KinCartesian, GimbalLockIsSingularAndKeepsA) {
  Cartesian k(6);
  const double q[6] = {0, 0, 0, 0.4, kPi / 2, 0.1};
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok);
  const double near[6] = {0, 0, 0, 0.4, 1.5, 0};
  double r[6];
  ASSERT_EQ(k.inverse(x, {}, near, r), KinStatus::Singular);
  EXPECT_NEAR(r[3], 0.4, 1e-12);
  Pose y;
  ASSERT_EQ(k.forward(r, y), KinStatus::Ok);
  EXPECT_LT(poseError(x, y), 1e-12);
}

TEST(KinCartesian, RandomRoundTrips) {
  for (int axes = 1; axes <= 6; ++axes) {
    Cartesian k(axes);
    std::mt19937_64 rng(seed() + axes);
    std::uniform_real_distribution<double> pos(-1000, 1000), ang(-kPi, kPi), tilt(-1.5, 1.5);
    RoundTripStats st;
    for (int n = 0; n < kSamples; ++n) {
      double q[6] = {pos(rng), pos(rng), pos(rng), ang(rng), tilt(rng), ang(rng)};
      roundTrip(k, q, 1000, st, n % 10 == 0, "cartesian");
    }
    expectStats(st, ("cartesian" + std::to_string(axes)).c_str());
    neverNaN(k, "cartesian");
  }
}

TEST(KinGantry, OffsetsAndRotation) {
  GantryParams p;
  p.axes = 3;
  p.offset = {10, 20, 30};
  p.rotation = kPi / 2;
  Gantry g(p);
  double q[3];
  ASSERT_EQ(g.inverse(poseAt(1, 0, 2), {}, nullptr, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], 10, 1e-12);   // x along the machine's -Y
  EXPECT_NEAR(q[1], 19, 1e-12);
  EXPECT_NEAR(q[2], 32, 1e-12);
  GantryParams p2;
  p2.axes = 2;
  p2.offset = {5, -5, 0};
  Gantry g2(p2);
  ASSERT_EQ(g2.inverse(poseAt(1, 2, 99), {}, nullptr, q), KinStatus::Ok);
  EXPECT_EQ(q[0], 6);
  EXPECT_EQ(q[1], -3);
  Pose x;
  ASSERT_EQ(g2.forward(q, x), KinStatus::Ok);
  EXPECT_EQ(x.p, Eigen::Vector3d(1, 2, 0));
  p2.offset.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Gantry(p2).valid());
}

TEST(KinGantry, RandomRoundTrips) {
  GantryParams p;
  p.offset = {12.5, -7, 3};
  p.rotation = 0.3;
  Gantry g(p);
  std::mt19937_64 rng(seed());
  std::uniform_real_distribution<double> pos(-1000, 1000);
  RoundTripStats st;
  for (int n = 0; n < kSamples; ++n) {
    double q[3] = {pos(rng), pos(rng), pos(rng)};
    roundTrip(g, q, 1000, st, n % 10 == 0, "gantry");
  }
  expectStats(st, "gantry3");
  neverNaN(g, "gantry3");
}

// ---------------------------------------------------------------- SCARA
TEST(KinScara, TwoJointClosedForms) {
  Scara2 k({100, 100});
  double q[2];
  ASSERT_EQ(k.inverse(poseAt(100, 100, 0), {1, 1, 1}, nullptr, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], 0, 1e-14);
  EXPECT_NEAR(q[1], kPi / 2, 1e-14);
  ASSERT_EQ(k.inverse(poseAt(100, 100, 0), {-1, 1, 1}, nullptr, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], kPi / 2, 1e-14);
  EXPECT_NEAR(q[1], -kPi / 2, 1e-14);
  EXPECT_EQ(k.inverse(poseAt(200.001, 0, 0), {}, nullptr, q), KinStatus::Unreachable);
  // Stretched: singular, B = 0.
  ASSERT_EQ(k.inverse(poseAt(0, 200, 0), {}, nullptr, q), KinStatus::Singular);
  EXPECT_NEAR(q[0], kPi / 2, 1e-14);
  EXPECT_NEAR(q[1], 0, 1e-14);
  // Folded onto the base (l1 == l2): A is free, taken from qNear.
  const double near[2] = {0.7, 3};
  ASSERT_EQ(k.inverse(poseAt(0, 0, 0), {}, near, q), KinStatus::Singular);
  EXPECT_EQ(q[0], 0.7);
  EXPECT_NEAR(std::abs(q[1]), kPi, 1e-12);
  // Unequal arms: the hole around the base is unreachable.
  Scara2 k2({100, 60});
  EXPECT_EQ(k2.inverse(poseAt(30, 0, 0), {}, nullptr, q), KinStatus::Unreachable);
  EXPECT_FALSE(Scara2({0, 1}).valid());
  EXPECT_FALSE(Scara2({-1, 1}).valid());
  EXPECT_EQ(Scara2({0, 1}).inverse(poseAt(1, 0, 0), {}, nullptr, q), KinStatus::InvalidParameters);
}

TEST(KinScara, JointLimitsAndNearestTurn) {
  Scara2 k({100, 100});
  const double lo[2] = {-kPi, 0}, hi[2] = {kPi, kPi / 3};
  ASSERT_TRUE(k.setJointLimits(lo, hi));
  double q[2] = {9, 9};
  EXPECT_EQ(k.inverse(poseAt(100, 100, 0), {1, 1, 1}, nullptr, q), KinStatus::JointLimit);
  EXPECT_EQ(q[0], 9);
  Scara2 k2({100, 100});
  const double near[2] = {2 * kPi, 0};   // one turn further on: A = 2 pi, not 0
  ASSERT_EQ(k2.inverse(poseAt(100, 100, 0), {1, 1, 1}, near, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], 2 * kPi, 1e-12);
  EXPECT_NEAR(q[1], kPi / 2, 1e-12);
}

TEST(KinScara, ThreeAndFourJointClosedForms) {
  Scara3 k({100, 100, 100});
  double q[4];
  // Approach from below (direction 90 deg): wrist at (100, 100).
  ASSERT_EQ(k.inverse(poseAt(100, 200, 0, kPi / 2), {1, 1, 1}, nullptr, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], 0, 1e-14);
  EXPECT_NEAR(q[1], kPi / 2, 1e-14);
  EXPECT_NEAR(q[2], 0, 1e-14);
  EXPECT_EQ(k.inverse(poseAt(400, 0, 0, kPi), {}, nullptr, q), KinStatus::Unreachable);
  Scara4 s4(Scara4Params{100, 100, 50, -1});
  ASSERT_EQ(s4.inverse(poseAt(100, 100, 20, kPi), {1, 1, 1}, nullptr, q), KinStatus::Ok);
  EXPECT_NEAR(q[0], 0, 1e-14);
  EXPECT_NEAR(q[1], kPi / 2, 1e-14);
  EXPECT_NEAR(q[2], 30, 1e-12);          // down 30 from z0 = 50
  EXPECT_NEAR(q[3], kPi / 2, 1e-14);     // tool at 180 deg = A + B + C
}

template <class K>
void scaraRandom(const K& k, int revoluteJoints, const char* what) {
  std::mt19937_64 rng(seed() + revoluteJoints);
  std::uniform_real_distribution<double> ang(-kPi, kPi), z(-200, 200);
  RoundTripStats st;
  for (int n = 0; n < kSamples; ++n) {
    double q[4] = {ang(rng), ang(rng), ang(rng), ang(rng)};
    if (std::abs(std::sin(q[1])) < 0.02) q[1] = 0.5;   // away from the stretched/folded arm
    if (k.joints() == 4) q[2] = z(rng);
    roundTrip(k, q, 1, st, true, what);
  }
  expectStats(st, what);
  neverNaN(k, what);
}

TEST(KinScara, RandomRoundTrips) {
  scaraRandom(Scara2({0.35, 0.25}), 2, "scara2");
  scaraRandom(Scara3({0.35, 0.25, 0.1}), 3, "scara3");
  scaraRandom(Scara4(Scara4Params{0.35, 0.25, 0.3, -1}), 4, "scara4");
}

// ---------------------------------------------------------------- delta
DeltaRotaryParams rotaryDelta() {
  DeltaRotaryParams p;   // the seed's example: 200 / 300 / 112 / 53 mm
  p.upperArm = 200;
  p.rod = 300;
  p.baseRadius = 112;
  p.platformRadius = 53;
  p.rotation = 0.2;
  return p;
}

TEST(KinDelta, RotaryClosedForms) {
  DeltaRotary k(rotaryDelta());
  ASSERT_TRUE(k.valid());
  EXPECT_NEAR(k.baseHeight(), std::sqrt(300.0 * 300 - 259.0 * 259), 1e-12);
  double q[3];
  ASSERT_EQ(k.inverse(poseAt(0, 0, 0), {}, nullptr, q), KinStatus::Ok);
  for (double v : q) EXPECT_NEAR(v, 0, 1e-14);
  // On the axis every arm has the same angle; lower means arms further down.
  ASSERT_EQ(k.inverse(poseAt(0, 0, -100), {}, nullptr, q), KinStatus::Ok);
  EXPECT_GT(q[0], 0);
  EXPECT_NEAR(q[1], q[0], 1e-13);
  EXPECT_NEAR(q[2], q[0], 1e-13);
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok);
  EXPECT_LT((x.p - Eigen::Vector3d(0, 0, -100)).norm(), 1e-11);
  EXPECT_EQ(k.inverse(poseAt(0, 0, -1000), {}, nullptr, q), KinStatus::Unreachable);
  EXPECT_EQ(k.inverse(poseAt(600, 0, -100), {}, nullptr, q), KinStatus::Unreachable);
  // Rod tilt out of the arm plane beyond the ball joints' range.
  DeltaRotaryParams p = rotaryDelta();
  p.maxBallJointAngle = 10 * kDeg;
  DeltaRotary lim(p);
  EXPECT_EQ(lim.inverse(poseAt(0, 0, -100), {}, nullptr, q), KinStatus::Ok);
  EXPECT_EQ(lim.inverse(poseAt(-150 * std::sin(0.2), 150 * std::cos(0.2), -150), {}, nullptr, q), KinStatus::JointLimit);
  // Geometry with no home pose (rod too short to reach horizontal arms).
  p.rod = 100;
  EXPECT_FALSE(DeltaRotary(p).valid());
}

TEST(KinDelta, LinearClosedForms) {
  DeltaLinearParams p;
  p.railRadius = 200;
  p.platformRadius = 40;
  p.rod = 300;
  DeltaLinear k(p);
  ASSERT_TRUE(k.valid());
  double q[3];
  ASSERT_EQ(k.inverse(poseAt(10, -20, -50), {}, nullptr, q), KinStatus::Ok);
  for (int i = 0; i < 3; ++i) {
    const double az = i * 2 * kPi / 3;
    const double dx = 160 * std::cos(az) - 10, dy = 160 * std::sin(az) + 20;
    EXPECT_NEAR(q[i], -50 + std::sqrt(300.0 * 300 - dx * dx - dy * dy), 1e-12);
  }
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok);
  EXPECT_LT((x.p - Eigen::Vector3d(10, -20, -50)).norm(), 1e-11);
  EXPECT_EQ(k.inverse(poseAt(500, 0, 0), {}, nullptr, q), KinStatus::Unreachable);
  // The rod perpendicular to the rail: singular.
  EXPECT_EQ(k.inverse(poseAt(160 - 300, 0, 0), {}, nullptr, q), KinStatus::Singular);
  p.railAngle = 2;   // > 90 deg
  EXPECT_FALSE(DeltaLinear(p).valid());
}

// Deltas are sampled in the workspace (a box below the base), then run joints -> pose -> joints.
template <class K>
void deltaRandom(const K& k, Eigen::Vector3d lo, Eigen::Vector3d hi, double scale, const char* what) {
  std::mt19937_64 rng(seed() + 11);
  std::uniform_real_distribution<double> u(0, 1);
  RoundTripStats st;
  int unreachable = 0;
  for (int n = 0; n < kSamples; ++n) {
    Pose x;
    for (int i = 0; i < 3; ++i) x.p[i] = lo[i] + (hi[i] - lo[i]) * u(rng);
    double q[3];
    const KinStatus s = k.inverse(x, {}, nullptr, q);
    ASSERT_EQ(s, KinStatus::Ok) << what << " at " << x.p.transpose();
    roundTrip(k, q, scale, st, true, what);
    // The other way too: pose -> joints -> pose.
    Pose y;
    ASSERT_EQ(k.forward(q, y), KinStatus::Ok);
    EXPECT_LE((y.p - x.p).cwiseAbs().maxCoeff(), 1e-12 * scale) << what;
  }
  EXPECT_EQ(unreachable, 0);
  expectStats(st, what);
  neverNaN(k, what);
}

TEST(KinDelta, RotaryRandomRoundTrips) {
  deltaRandom(DeltaRotary(rotaryDelta()), {-80, -80, -250}, {80, 80, -60}, 300, "delta_rotary");
}

TEST(KinDelta, LinearRandomRoundTrips) {
  DeltaLinearParams p;
  p.railRadius = 200;
  p.platformRadius = 40;
  p.rod = 300;
  p.rotation = -0.4;
  deltaRandom(DeltaLinear(p), {-100, -100, -300}, {100, 100, 100}, 300, "delta_linear");
  p.railAngle = 15 * kDeg;
  deltaRandom(DeltaLinear(p), {-80, -80, -300}, {80, 80, 0}, 300, "delta_linear_tilted");
}

// ---------------------------------------------------------------- 6R arm
DhTable industrialArm() {
  DhTable dh;
  dh[0] = {0.15, -kPi / 2, 0.45, 0};
  dh[1] = {0.6, 0, 0, -kPi / 2};
  dh[2] = {0.12, -kPi / 2, 0, 0};
  dh[3] = {0, kPi / 2, 0.64, 0};
  dh[4] = {0, -kPi / 2, 0, 0};
  dh[5] = {0, 0, 0.1, 0};
  return dh;
}

DhTable offsetArm() {   // lateral shoulder offset, other signs, a tool offset a6 / alpha6
  DhTable dh;
  dh[0] = {0.05, kPi / 2, 0.3, 0.1};
  dh[1] = {0.43, 0, 0.15, 0};
  dh[2] = {-0.02, kPi / 2, -0.05, 0.2};
  dh[3] = {0, -kPi / 2, 0.43, 0};
  dh[4] = {0, -kPi / 2, 0, -0.3};
  dh[5] = {0.03, 0.4, 0.07, 0.5};
  return dh;
}

TEST(KinArticulated, EightConfigurations) {
  Articulated6 k(industrialArm());
  ASSERT_TRUE(k.valid());
  const double q0[6] = {0.3, -0.4, 0.5, 0.6, -0.7, 0.8};
  Pose x;
  ASSERT_EQ(k.forward(q0, x), KinStatus::Ok);
  int distinct = 0;
  std::vector<std::array<double, 6>> sols;
  for (int8_t e : {1, -1})
    for (int8_t s : {1, -1})
      for (int8_t w : {1, -1}) {
        const Config c{e, s, w};
        double q[6];
        ASSERT_EQ(k.inverse(x, c, nullptr, q), KinStatus::Ok);
        Pose y;
        ASSERT_EQ(k.forward(q, y), KinStatus::Ok);
        EXPECT_LT(poseError(x, y), 1e-12);
        EXPECT_EQ(k.configOf(q), c);
        std::array<double, 6> a;
        std::copy(q, q + 6, a.begin());
        bool fresh = true;
        for (auto& b : sols) {
          double d = 0;
          for (int i = 0; i < 6; ++i) d = std::max(d, std::abs(wrapPi(a[i] - b[i])));
          fresh = fresh && d > 1e-6;
        }
        distinct += fresh;
        sols.push_back(a);
      }
  EXPECT_EQ(distinct, 8);
  // Home: with these offsets q = 0 points the arm up, the flange at a closed-form point.
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  ASSERT_EQ(k.forward(zero, x), KinStatus::Ok);
  EXPECT_NEAR(x.p.x(), 0.15 + 0.64 + 0.1, 1e-12);   // a1 + d4 + d6 along x after the elbow
  EXPECT_NEAR(x.p.y(), 0, 1e-12);
  EXPECT_NEAR(x.p.z(), 0.45 + 0.6 + 0.12, 1e-12);
}

TEST(KinArticulated, SingularAndUnreachable) {
  Articulated6 k(industrialArm());
  // q5 = 0: wrist singular, q4 kept from qNear.
  const double q0[6] = {0.3, -0.4, 0.5, 0.6, 0, 0.8};
  Pose x;
  ASSERT_EQ(k.forward(q0, x), KinStatus::Ok);
  double q[6];
  ASSERT_EQ(k.inverse(x, {1, 1, 1}, q0, q), KinStatus::Singular);
  EXPECT_NEAR(q[3], 0.6, 1e-12);
  Pose y;
  ASSERT_EQ(k.forward(q, y), KinStatus::Ok);
  EXPECT_LT(poseError(x, y), 1e-12);
  EXPECT_EQ(k.inverse(poseAt(5, 0, 0), {}, nullptr, q), KinStatus::Unreachable);
  DhTable bad = industrialArm();
  bad[1].alpha = 0.1;
  EXPECT_FALSE(Articulated6(bad).valid());
  bad = industrialArm();
  bad[4].d = 0.01;   // not a spherical wrist
  EXPECT_FALSE(Articulated6(bad).valid());
}

void articulatedRandom(const DhTable& dh, const char* what) {
  Articulated6 k(dh);
  ASSERT_TRUE(k.valid());
  std::mt19937_64 rng(seed() + 6);
  std::uniform_real_distribution<double> ang(-kPi, kPi);
  const double beta = std::atan2(-(dh[2].alpha > 0 ? 1 : -1) * dh[3].d, dh[2].a);
  const double lateral = dh[1].d + dh[2].d;
  RoundTripStats st;
  for (int n = 0; n < kSamples;) {
    double q[6];
    for (double& v : q) v = ang(rng);
    // Keep away from the three singularities (they amplify rounding by 1/distance).
    std::array<Eigen::Isometry3d, 7> T;
    k.frames(q, T);
    const Eigen::Vector3d w = T[4].translation();
    const double reach = std::sqrt(std::max(0.0, w.x() * w.x() + w.y() * w.y() - lateral * lateral));
    if (std::abs(std::sin(q[4] + dh[4].thetaOffset)) < 0.05 || std::abs(std::sin(q[2] + dh[2].thetaOffset + beta)) < 0.05 ||
        reach < 0.05)
      continue;
    roundTrip(k, q, 1, st, true, what);
    ++n;
  }
  expectStats(st, what);
  neverNaN(k, what);
}

TEST(KinArticulated, RandomRoundTrips) {
  articulatedRandom(industrialArm(), "6r_industrial");
  articulatedRandom(offsetArm(), "6r_offsets");
}

// ---------------------------------------------------------------- Stewart
StewartParams hexapod() { return StewartParams::symmetric(1.0, 0.6, 10 * kDeg, 10 * kDeg, 1.2); }

TEST(KinStewart, HomeAndClosedForms) {
  Stewart k(hexapod());
  ASSERT_TRUE(k.valid());
  double q[6];
  ASSERT_EQ(k.inverse(k.params().home, {}, nullptr, q), KinStatus::Ok);
  // By symmetry every leg has the same length at home.
  const StewartParams& p = k.params();
  const double l = std::sqrt(1.2 * 1.2 + (p.platform[0] - p.base[0]).squaredNorm());
  for (double v : q) EXPECT_NEAR(v, l, 1e-14);
  Pose x;
  ASSERT_EQ(k.forward(q, x), KinStatus::Ok);
  EXPECT_LT(poseError(x, p.home), 1e-14);
  // Lengths no platform can take: no convergence or singular, never a pose.
  const double bad[6] = {0.01, 0.01, 0.01, 3, 3, 3};
  const KinStatus s = k.forward(bad, x);
  EXPECT_TRUE(s == KinStatus::NoConvergence || s == KinStatus::Singular) << statusName(s);
  const double neg[6] = {-1, l, l, l, l, l};
  EXPECT_EQ(k.forward(neg, x), KinStatus::Unreachable);
  // An iteration limit of 1 from far away: NoConvergence.
  StewartParams p1 = hexapod();
  p1.maxIterations = 1;
  Stewart k1(p1);
  Pose far = p1.home;
  far.p.x() += 0.2;
  far.R = rotZ(0.2);
  ASSERT_EQ(k1.inverse(far, {}, nullptr, q), KinStatus::Ok);
  EXPECT_EQ(k1.forward(q, x), KinStatus::NoConvergence);
  EXPECT_EQ(k1.forwardFrom(q, far, x), KinStatus::Ok);
}

TEST(KinStewart, RandomRoundTrips) {
  Stewart k(hexapod());
  std::mt19937_64 rng(seed() + 66);
  std::uniform_real_distribution<double> u(-1, 1);
  RoundTripStats st;
  double maxJac = 0;
  for (int n = 0; n < kSamples; ++n) {
    Pose x = k.params().home;
    x.p += 0.15 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Vector3d rv = 0.15 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    x.R = Eigen::AngleAxisd(rv.norm(), rv.normalized()).toRotationMatrix();
    double q[6];
    ASSERT_EQ(k.inverse(x, {}, nullptr, q), KinStatus::Ok);
    Pose y;
    ASSERT_EQ(k.forward(q, y), KinStatus::Ok);
    EXPECT_LE(poseError(x, y), 1e-12);
    roundTrip(k, q, 1, st, false, "stewart");
    if (n % 10 == 0) {
      // Forward Jacobian times central differences of the closed-form inverse = identity.
      Jacobian J;
      k.jacobian(q, J);
      Eigen::Matrix<double, 6, 6> D;
      const double h = 1e-6;
      for (int j = 0; j < 6; ++j) {
        Pose a = y, b = y;
        if (j < 3) {
          a.p[j] += h;
          b.p[j] -= h;
        } else {
          a.R = Eigen::AngleAxisd(h, Eigen::Vector3d::Unit(j - 3)).toRotationMatrix() * y.R;
          b.R = Eigen::AngleAxisd(-h, Eigen::Vector3d::Unit(j - 3)).toRotationMatrix() * y.R;
        }
        double qa[6], qb[6];
        ASSERT_EQ(k.inverse(a, {}, nullptr, qa), KinStatus::Ok);
        ASSERT_EQ(k.inverse(b, {}, nullptr, qb), KinStatus::Ok);
        for (int i = 0; i < 6; ++i) D(i, j) = (qa[i] - qb[i]) / (2 * h);
      }
      maxJac = std::max(maxJac, (D * Eigen::Matrix<double, 6, 6>(J) - Eigen::Matrix<double, 6, 6>::Identity()).cwiseAbs().maxCoeff());
    }
  }
  expectStats(st, "stewart");
  std::printf("[ stats    ] stewart Jacobian x FD(inverse) - I: %.2e\n", maxJac);
  EXPECT_LE(maxJac, 1e-6);
  neverNaN(k, "stewart");
}

TEST(KinBase, InvalidInputs) {
  Scara2 k({1, 1});
  const double nanq[2] = {std::numeric_limits<double>::quiet_NaN(), 0};
  Pose x;
  EXPECT_EQ(k.forward(nanq, x), KinStatus::InvalidParameters);
  double q[2];
  EXPECT_EQ(k.inverse(poseAt(std::numeric_limits<double>::infinity(), 0, 0), {}, nullptr, q),
            KinStatus::InvalidParameters);
  EXPECT_EQ(k.inverse(poseAt(1, 0, 0), {}, nanq, q), KinStatus::InvalidParameters);
  const double lo[2] = {1, 0}, hi[2] = {0, 1};
  EXPECT_FALSE(k.setJointLimits(lo, hi));
  EXPECT_STREQ(statusName(KinStatus::NoConvergence), "NoConvergence");
}

}  // namespace

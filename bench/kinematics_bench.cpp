// Kinematic models (stdlib-motion/kinematics): ns per forward and inverse
// transformation, cycling through 1024 precomputed reachable poses/joints.
#include <benchmark/benchmark.h>

#include <array>
#include <numbers>
#include <random>
#include <vector>

#include "stdlib-motion/kinematics/Articulated.h"
#include "stdlib-motion/kinematics/Delta.h"
#include "stdlib-motion/kinematics/Scara.h"
#include "stdlib-motion/kinematics/Stewart.h"

using namespace stc::motion::kin;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr size_t kN = 1024;

struct Samples {
  std::vector<std::array<double, 6>> q;
  std::vector<Pose> x;
  std::vector<Config> c;
};

// Joint samples from poses drawn by `pose`, kept when the inverse succeeds.
template <class PoseGen>
Samples samples(const Kinematics& k, PoseGen pose) {
  Samples s;
  std::mt19937_64 rng(42);
  while (s.q.size() < kN) {
    Pose x = pose(rng);
    std::array<double, 6> q{};
    if (k.inverse(x, {}, nullptr, q.data()) != KinStatus::Ok) continue;
    s.q.push_back(q);
    s.x.push_back(x);
    s.c.push_back(k.configOf(q.data()));
  }
  return s;
}

const Scara2& scara() {
  static Scara2 k({0.35, 0.25});
  return k;
}
const DeltaRotary& delta() {
  static DeltaRotary k([] {
    DeltaRotaryParams p;
    p.upperArm = 200;
    p.rod = 300;
    p.baseRadius = 112;
    p.platformRadius = 53;
    return p;
  }());
  return k;
}
const Articulated6& arm() {
  static Articulated6 k([] {
    DhTable dh;
    dh[0] = {0.15, -kPi / 2, 0.45, 0};
    dh[1] = {0.6, 0, 0, -kPi / 2};
    dh[2] = {0.12, -kPi / 2, 0, 0};
    dh[3] = {0, kPi / 2, 0.64, 0};
    dh[4] = {0, -kPi / 2, 0, 0};
    dh[5] = {0, 0, 0.1, 0};
    return dh;
  }());
  return k;
}
const Stewart& hexapod() {
  static Stewart k(StewartParams::symmetric(1.0, 0.6, 10 * kPi / 180, 10 * kPi / 180, 1.2));
  return k;
}

std::uniform_real_distribution<double> unit(-1, 1);

const Samples& scaraSamples() {
  static Samples s = samples(scara(), [](std::mt19937_64& r) {
    Pose x;
    x.p = {0.5 * unit(r), 0.5 * unit(r), 0};
    return x;
  });
  return s;
}
const Samples& deltaSamples() {
  static Samples s = samples(delta(), [](std::mt19937_64& r) {
    Pose x;
    x.p = {80 * unit(r), 80 * unit(r), -150 + 90 * unit(r)};
    return x;
  });
  return s;
}
const Samples& armSamples() {
  static Samples s = [] {
    Samples s;
    std::mt19937_64 r(42);
    while (s.q.size() < kN) {
      std::array<double, 6> q;
      for (double& v : q) v = kPi * unit(r);
      Pose x;
      arm().forward(q.data(), x);
      s.q.push_back(q);
      s.x.push_back(x);
      s.c.push_back(arm().configOf(q.data()));
    }
    return s;
  }();
  return s;
}
const Samples& hexapodSamples() {
  static Samples s = samples(hexapod(), [](std::mt19937_64& r) {
    Pose x = hexapod().params().home;
    x.p += 0.15 * Eigen::Vector3d(unit(r), unit(r), unit(r));
    const Eigen::Vector3d w = 0.15 * Eigen::Vector3d(unit(r), unit(r), unit(r));
    x.R = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    return x;
  });
  return s;
}

void forward(benchmark::State& st, const Kinematics& k, const Samples& s) {
  size_t i = 0;
  Pose x;
  for (auto _ : st) {
    benchmark::DoNotOptimize(k.forward(s.q[i].data(), x));
    benchmark::DoNotOptimize(x);
    i = (i + 1) % kN;
  }
}

void inverse(benchmark::State& st, const Kinematics& k, const Samples& s) {
  size_t i = 0;
  std::array<double, 6> q;
  for (auto _ : st) {
    benchmark::DoNotOptimize(k.inverse(s.x[i], s.c[i], s.q[i].data(), q.data()));
    benchmark::DoNotOptimize(q);
    i = (i + 1) % kN;
  }
}

void jacobian(benchmark::State& st, const Kinematics& k, const Samples& s) {
  size_t i = 0;
  Jacobian J;
  for (auto _ : st) {
    k.jacobian(s.q[i].data(), J);
    benchmark::DoNotOptimize(J);
    i = (i + 1) % kN;
  }
}

}  // namespace

BENCHMARK_CAPTURE(forward, scara2, scara(), scaraSamples());
BENCHMARK_CAPTURE(inverse, scara2, scara(), scaraSamples());
BENCHMARK_CAPTURE(forward, delta_rotary, delta(), deltaSamples());
BENCHMARK_CAPTURE(inverse, delta_rotary, delta(), deltaSamples());
BENCHMARK_CAPTURE(jacobian, delta_rotary, delta(), deltaSamples());
BENCHMARK_CAPTURE(forward, arm_6r, arm(), armSamples());
BENCHMARK_CAPTURE(inverse, arm_6r, arm(), armSamples());
BENCHMARK_CAPTURE(jacobian, arm_6r, arm(), armSamples());
BENCHMARK_CAPTURE(forward, stewart_newton, hexapod(), hexapodSamples());
BENCHMARK_CAPTURE(inverse, stewart, hexapod(), hexapodSamples());

BENCHMARK_MAIN();

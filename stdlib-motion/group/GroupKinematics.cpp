// Group kinematics and coordinate frames (GroupKinematics.h).
#include "stdlib-motion/group/GroupKinematics.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Kernel.h"
#include "stdlib-motion/group/AxisGroup.h"
#include "stdlib-motion/kinematics/Articulated.h"
#include "stdlib-motion/kinematics/Cartesian.h"
#include "stdlib-motion/kinematics/Delta.h"
#include "stdlib-motion/kinematics/Scara.h"

namespace stc::motion {

namespace {
constexpr double kDeg = M_PI / 180.0;

Eigen::Matrix3d rotationOf(const Frame& f) {
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = f.R[3 * r + c];
  return R;
}
void setRotation(Frame& f, const Eigen::Matrix3d& R) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f.R[3 * r + c] = R(r, c);
}
Eigen::Matrix3d rotationAbc(double a, double b, double c) {
  return (Eigen::AngleAxisd(a * kDeg, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(c * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}
double nearTurn(double deg, double ref) { return deg + 360.0 * std::round((ref - deg) / 360.0); }
}  // namespace

bool validCoordSystem(int cs) { return cs >= 0 && cs <= 5; }

bool Frame::fromCoords(const double* x, Frame& out) {
  for (int i = 0; i < 6; ++i)
    if (!bounds::position(x[i])) return false;
  out = Frame{};
  setRotation(out, rotationAbc(x[3], x[4], x[5]));
  std::copy(x, x + 3, out.p);
  return true;
}

void Frame::toCoords(double* x, const double* nearAbc) const {
  const Eigen::Matrix3d R = rotationOf(*this);
  // R = Rz(A) Ry(B) Rx(C): B from -R20; at B = +-90 degrees (gimbal lock) C is 0.
  const double b = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  double a, c;
  if (std::hypot(R(0, 0), R(1, 0)) < 1e-12) {
    a = std::atan2(-R(0, 1), R(1, 1));
    c = 0;
  } else {
    a = std::atan2(R(1, 0), R(0, 0));
    c = std::atan2(R(2, 1), R(2, 2));
  }
  std::copy(p, p + 3, x);
  x[3] = a / kDeg;
  x[4] = b / kDeg;
  x[5] = c / kDeg;
  if (nearAbc)
    for (int i = 3; i < 6; ++i) x[i] = nearTurn(x[i], nearAbc[i - 3]);
  for (int i = 3; i < 6; ++i)
    if (std::fabs(x[i]) < 1e-13) x[i] = 0;   // no -0 or 1e-17 noise from the rotation
}

Frame Frame::operator*(const Frame& o) const {
  Frame f;
  setRotation(f, rotationOf(*this) * rotationOf(o));
  point(o.p, f.p);
  return f;
}

Frame Frame::inverse() const {
  Frame f;
  const Eigen::Matrix3d Rt = rotationOf(*this).transpose();
  setRotation(f, Rt);
  const Eigen::Vector3d t = -(Rt * Eigen::Vector3d(p[0], p[1], p[2]));
  for (int i = 0; i < 3; ++i) f.p[i] = t[i];
  return f;
}

void Frame::vector(const double* in, double* out) const {
  double r[3];
  for (int i = 0; i < 3; ++i) r[i] = R[3 * i] * in[0] + R[3 * i + 1] * in[1] + R[3 * i + 2] * in[2];
  std::copy(r, r + 3, out);
}

void Frame::point(const double* in, double* out) const {
  vector(in, out);
  for (int i = 0; i < 3; ++i) out[i] += p[i];
}

// ---------------------------------------------------------------- the models

struct GroupKinematics::Impl {
  KinSpec spec;
  std::unique_ptr<kin::Kinematics> model;   // the arm (Scara2Z: without its Z axis)
  int joints = 0;
  unsigned controlled = 0;
  double offset[6] = {};   // axis = joint + offset (degrees for revolute joints)
  bool revolute[6] = {};
};

GroupKinematics::GroupKinematics(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GroupKinematics::~GroupKinematics() = default;
const KinSpec& GroupKinematics::spec() const { return impl_->spec; }
int GroupKinematics::joints() const { return impl_->joints; }
unsigned GroupKinematics::controlled() const { return impl_->controlled; }

std::shared_ptr<const GroupKinematics> GroupKinematics::make(const KinSpec& spec) {
  for (double v : spec.param)
    if (!bounds::position(v)) return nullptr;
  auto im = std::make_unique<Impl>();
  im->spec = spec;
  const double* p = spec.param;
  switch (spec.model) {
    case KinModel::Gantry2:
    case KinModel::Gantry3: {
      // The offsets are applied here like every model's (axis = coordinate + offset).
      kin::GantryParams gp;
      gp.axes = spec.model == KinModel::Gantry2 ? 2 : 3;
      im->model = std::make_unique<kin::Gantry>(gp);
      im->joints = gp.axes;
      im->controlled = gp.axes == 2 ? 0b11u : 0b111u;
      std::copy(p, p + gp.axes, im->offset);
      break;
    }
    case KinModel::Scara2Z:
      im->model = std::make_unique<kin::Scara2>(kin::Scara2Params{p[0], p[1]});
      im->joints = 3;
      im->controlled = 0b111u;
      std::copy(p + 2, p + 5, im->offset);
      im->revolute[0] = im->revolute[1] = true;
      break;
    case KinModel::TripodRotary: {
      kin::DeltaRotaryParams dp;
      dp.baseRadius = p[0];
      dp.platformRadius = p[1];
      dp.upperArm = p[2];
      dp.rod = p[3];
      dp.rotation = p[4] * kDeg;
      im->model = std::make_unique<kin::DeltaRotary>(dp);
      im->joints = 3;
      im->controlled = 0b111u;
      std::copy(p + 5, p + 8, im->offset);
      im->revolute[0] = im->revolute[1] = im->revolute[2] = true;
      break;
    }
    case KinModel::TripodLinear: {
      kin::DeltaLinearParams dp;
      dp.railRadius = p[0];
      dp.platformRadius = p[1];
      dp.rod = p[2];
      dp.railAngle = p[3] * kDeg;
      dp.rotation = p[4] * kDeg;
      im->model = std::make_unique<kin::DeltaLinear>(dp);
      im->joints = 3;
      im->controlled = 0b111u;
      std::copy(p + 5, p + 8, im->offset);
      break;
    }
    case KinModel::Scara3Z:
      im->model = std::make_unique<kin::Scara3>(kin::Scara3Params{p[0], p[1], p[2]});
      im->joints = 4;
      im->controlled = 0b1111u;   // X, Y, Z and A (the tool's direction about Z)
      std::copy(p + 3, p + 7, im->offset);
      im->revolute[0] = im->revolute[1] = im->revolute[2] = true;
      break;
    case KinModel::Articulated6: {
      const double d1 = p[0], a1 = p[1], a2 = p[2], d3 = p[3], a3 = p[4], d4 = p[5], d6 = p[6];
      const kin::DhTable dh{{{a1, 90 * kDeg, d1, 0}, {a2, 0, 0, 90 * kDeg}, {a3, 90 * kDeg, d3, 0},
                             {0, 90 * kDeg, d4, 0}, {0, -90 * kDeg, 0, 0}, {0, 0, d6, 0}}};
      im->model = std::make_unique<kin::Articulated6>(dh);
      im->joints = 6;
      im->controlled = 0b111111u;
      std::copy(p + 7, p + 13, im->offset);
      std::fill(im->revolute, im->revolute + 6, true);
      break;
    }
  }
  if (!im->model || !im->model->valid()) return nullptr;
  return std::shared_ptr<const GroupKinematics>(new GroupKinematics(std::move(im)));
}

namespace {
// Joint values of the model (radians, offsets removed) from axis positions, and back.
void modelJoints(const GroupKinematics::Impl& im, const double* q, double* m) {
  for (int i = 0; i < im.joints; ++i) m[i] = (q[i] - im.offset[i]) * (im.revolute[i] ? kDeg : 1.0);
}
void axisPositions(const GroupKinematics::Impl& im, const double* m, double* q) {
  for (int i = 0; i < im.joints; ++i) q[i] = m[i] / (im.revolute[i] ? kDeg : 1.0) + im.offset[i];
}
bool usable(kin::KinStatus s) { return s == kin::KinStatus::Ok || s == kin::KinStatus::Singular; }
}  // namespace

bool GroupKinematics::forward(const double* q, double* x) const {
  const Impl& im = *impl_;
  double m[kin::kMaxJoints] = {};
  for (int i = 0; i < im.joints; ++i)
    if (!std::isfinite(q[i])) return false;
  modelJoints(im, q, m);
  kin::Pose pose;
  if (!usable(im.model->forward(m, pose))) return false;
  std::fill(x, x + 6, 0.0);
  for (int i = 0; i < 3; ++i)
    if (im.controlled & (1u << i)) x[i] = pose.p[i];
  if (im.spec.model == KinModel::Scara2Z) x[2] = m[2];   // the Z axis
  if (im.spec.model == KinModel::Scara3Z) {
    x[2] = m[3];
    x[3] = std::atan2(pose.R(1, 0), pose.R(0, 0)) / kDeg;
  }
  if (im.spec.model == KinModel::Articulated6) {
    Frame f;
    setRotation(f, pose.R);
    double xyzabc[6];
    f.toCoords(xyzabc);
    std::copy(xyzabc + 3, xyzabc + 6, x + 3);
  }
  for (int i = 0; i < 6; ++i)
    if (std::fabs(x[i]) < 1e-13) x[i] = 0;
  return true;
}

bool GroupKinematics::inverse(const double* x, const KinConfigData& c, const double* qNear, double* q) const {
  const Impl& im = *impl_;
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(x[i])) return false;
  kin::Pose pose;
  pose.p = Eigen::Vector3d(x[0], x[1], x[2]);
  const kin::Config cfg{kin::branch(static_cast<int8_t>(c.elbow < 0 ? -1 : 1)), kin::branch(static_cast<int8_t>(c.shoulder < 0 ? -1 : 1)),
                        kin::branch(static_cast<int8_t>(c.wrist < 0 ? -1 : 1))};
  double near[kin::kMaxJoints] = {}, m[kin::kMaxJoints] = {};
  if (qNear) modelJoints(im, qNear, near);
  if (im.spec.model == KinModel::Scara2Z || im.spec.model == KinModel::Scara3Z) pose.p.z() = 0;
  if (im.spec.model == KinModel::Scara3Z) pose.R = rotationAbc(x[3], 0, 0);
  if (im.spec.model == KinModel::Articulated6) pose.R = rotationAbc(x[3], x[4], x[5]);
  if (!usable(im.model->inverse(pose, cfg, qNear ? near : nullptr, m))) return false;
  if (im.spec.model == KinModel::Scara2Z) m[2] = x[2];
  if (im.spec.model == KinModel::Scara3Z) m[3] = x[2];
  axisPositions(im, m, q);
  return true;
}

KinConfigData GroupKinematics::configOf(const double* q) const {
  double m[kin::kMaxJoints] = {};
  modelJoints(*impl_, q, m);
  const kin::Config c = impl_->model->configOf(m);
  return KinConfigData{c.elbow, c.shoulder, c.wrist};
}

// ---------------------------------------------------------------- coordinate systems

bool cartesian(const AxisGroup& g, CoordSystem cs) { return g.kin && cs != CoordSystem::ACS; }

int coordCount(const AxisGroup& g, CoordSystem cs) {
  const int n = static_cast<int>(g.axes().size());
  return cartesian(g, cs) ? 6 + std::max(0, n - g.kin->joints()) : n;
}

namespace {

// The tool of group g in WCS for member positions q.
bool toolInWorld(const AxisGroup& g, const double* q, Frame& out) {
  double x[6] = {};
  if (g.kin) {
    if (!g.kin->forward(q, x)) return false;
  } else {
    for (size_t i = 0; i < std::min<size_t>(3, g.axes().size()); ++i) x[i] = q[i];
  }
  Frame tool;
  if (!Frame::fromCoords(x, tool)) return false;
  out = g.mcs * tool;
  return true;
}

// Coordinates in MCS <-> in the Cartesian system whose frame in WCS is f (through WCS).
// Without kinematics only the first three members move with the frame.
void mapCoords(const AxisGroup& g, const Frame& f, const double* in, double* out, const double* nearAbc) {
  const int n = coordCount(g, CoordSystem::MCS);
  std::copy(in, in + n, out);
  if (!g.kin) {
    double p[3] = {};
    const int m = std::min(3, n);
    std::copy(in, in + m, p);
    f.point(p, p);
    std::copy(p, p + m, out);
    return;
  }
  Frame pose;
  Frame::fromCoords(in, pose);
  (f * pose).toCoords(out, nearAbc);
}

}  // namespace

bool frameInWorld(const Kernel& k, const AxisGroup& g, CoordSystem cs, Frame& out) {
  switch (cs) {
    case CoordSystem::WCS: out = Frame{}; return true;
    case CoordSystem::MCS: out = g.mcs; return true;
    case CoordSystem::PCS1:
    case CoordSystem::PCS2: {
      const AxisGroup::Pcs& pcs = g.pcs[cs == CoordSystem::PCS1 ? 0 : 1];
      if (pcs.master == UINT32_MAX) {
        out = pcs.frame;
        return true;
      }
      // Dynamic: the master's tool now (its members' set positions), then the offset frame.
      const AxisGroup* m = k.group(pcs.master);
      if (!m || m == &g || m->axes().empty()) return false;
      double q[kMaxGroupAxes] = {};
      for (size_t i = 0; i < m->axes().size(); ++i) q[i] = m->axes()[i]->set().p;
      Frame tool;
      if (!toolInWorld(*m, q, tool)) return false;
      out = tool * pcs.frame;
      return true;
    }
    default: return false;
  }
}

bool convertCoords(const Kernel& k, const AxisGroup& g, CoordSystem from, CoordSystem to, const double* x, double* out) {
  Frame ff, ft;
  if (from == to && from != CoordSystem::ACS && from != CoordSystem::TCS) {
    // The same system: no frames to compose (the path step converts MCS to MCS every cycle).
    if (!frameInWorld(k, g, from, ff)) return false;
    std::copy(x, x + coordCount(g, CoordSystem::MCS), out);
  } else {
    if (!frameInWorld(k, g, from, ff) || !frameInWorld(k, g, to, ft)) return false;
    const double* near = x + 3;
    mapCoords(g, ft.inverse() * ff, x, out, g.kin ? near : nullptr);
  }
  // In MCS the coordinates the kinematics does not set are 0 (a rotated PCS gives them values).
  if (to == CoordSystem::MCS && g.kin)
    for (int i = 0; i < 6; ++i)
      if (!(g.kin->controlled() & (1u << i))) out[i] = 0;
  return true;
}

namespace {
// ACS to ACS is a copy and TCS holds no positions: true when cs is one of them (ok: the result).
bool noConversion(const AxisGroup& g, CoordSystem cs, const double* in, double* out, bool& ok) {
  ok = cs == CoordSystem::ACS;
  if (ok) std::copy(in, in + g.axes().size(), out);
  return cs == CoordSystem::ACS || cs == CoordSystem::TCS;
}
}  // namespace

bool coordsOf(const Kernel& k, const AxisGroup& g, CoordSystem cs, const double* q, double* x) {
  const size_t n = g.axes().size();
  if (bool ok; noConversion(g, cs, q, x, ok)) return ok;
  double mcs[kMaxGroupAxes] = {};
  if (g.kin) {
    if (!g.kin->forward(q, mcs)) return false;
    for (size_t i = g.kin->joints(); i < n; ++i) mcs[6 + i - g.kin->joints()] = q[i];
  } else {
    std::copy(q, q + n, mcs);
  }
  return convertCoords(k, g, CoordSystem::MCS, cs, mcs, x);
}

bool jointsOf(const Kernel& k, const AxisGroup& g, CoordSystem cs, const double* x, const KinConfigData& c, const double* qNear,
              double* q) {
  const size_t n = g.axes().size();
  if (bool ok; noConversion(g, cs, x, q, ok)) return ok;
  double mcs[kMaxGroupAxes] = {};
  if (!convertCoords(k, g, cs, CoordSystem::MCS, x, mcs)) return false;
  if (!g.kin) {
    std::copy(mcs, mcs + n, q);
    return true;
  }
  if (!g.kin->inverse(mcs, c, qNear, q)) return false;
  for (size_t i = g.kin->joints(); i < n; ++i) q[i] = mcs[6 + i - g.kin->joints()];
  return true;
}

}  // namespace stc::motion

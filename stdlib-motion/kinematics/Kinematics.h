// The kinematics library: one model object per mechanism, mapping joint
// positions (radians for revolute joints, length units for prismatic ones) to
// the tool pose in the base frame and back.  Models live in Cartesian.h,
// Scara.h, Delta.h, Articulated.h and Stewart.h; docs/kinematics.md has the
// conventions of each.  Eigen stays in this library (core headers do not see it).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>

namespace stc::motion::kin {

// The tool frame in the base frame: position p and orientation R (columns =
// the tool's axes).  Models with fewer than six degrees of freedom read only
// the components they control (documented per model) and ignore the rest.
struct Pose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

enum class KinStatus : uint8_t {
  Ok,
  Unreachable,        // no joint values give this pose (or these joints give no pose)
  Singular,           // a solution was written, but the Jacobian is rank deficient there
  JointLimit,         // the solution leaves a configured joint range
  NoConvergence,      // an iterative solve (Stewart forward) hit its iteration limit
  InvalidParameters,  // non-finite input, or a model built from bad parameters
};
const char* statusName(KinStatus s);

// Branch choices of a closed-form inverse, each +1 or -1 (0 reads as +1).
// Which joint sign each one selects is documented per model.
struct Config {
  int8_t elbow = 1, shoulder = 1, wrist = 1;
  bool operator==(const Config&) const = default;
};

inline constexpr int kMaxJoints = 6;
// 6 x n, n <= 6, without heap allocation.
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, kMaxJoints>;

// Base of every model.  The public calls check their arguments (finite
// numbers, a valid model) and the joint limits, and leave the outputs alone
// unless they return Ok or Singular; the models implement the solve*.
class Kinematics {
 public:
  virtual ~Kinematics() = default;

  int joints() const { return joints_; }
  // False when the construction parameters were rejected; every call then
  // returns InvalidParameters.
  bool valid() const { return valid_; }

  KinStatus forward(const double* q, Pose& out) const;
  // qNear (may be null): revolute joints are shifted by whole turns to the
  // representative nearest to it (else to (-pi, pi]); iterative models start there.
  KinStatus inverse(const Pose& x, const Config& c, const double* qNear, double* q) const;
  // The branches of the configuration the joints are in (inverse(forward(q), configOf(q)) == q).
  virtual Config configOf(const double* q) const { return {}; }
  // Columns: d(v, w)/dq_i, v = tool origin velocity, w = angular velocity, both in the base frame.
  void jacobian(const double* q, Jacobian& J) const;
  // The same by central differences of forward() (the default of jacobianOf; tests compare).
  void numericJacobian(const double* q, Jacobian& J, double h = 1e-6) const;

  // Joint ranges checked by inverse() (default unlimited; lo <= hi, finite or infinite).
  bool setJointLimits(const double* lo, const double* hi);
  bool revolute(int i) const { return (revoluteMask_ >> i) & 1u; }

 protected:
  Kinematics(int joints, unsigned revoluteMask) : joints_(joints), revoluteMask_(revoluteMask) {}
  void invalidate() { valid_ = false; }

  virtual KinStatus solveForward(const double* q, Pose& out) const = 0;
  virtual KinStatus solveInverse(const Pose& x, const Config& c, const double* qNear, double* q) const = 0;
  virtual void jacobianOf(const double* q, Jacobian& J) const { numericJacobian(q, J); }

 private:
  int joints_;
  unsigned revoluteMask_;
  bool valid_ = true;
  std::array<double, kMaxJoints> lo_, hi_;
  bool limited_ = false;
};

// ---- small helpers shared by the models
inline int8_t branch(int8_t c) { return c < 0 ? -1 : 1; }
inline int8_t signOf(double v) { return v < 0 ? -1 : 1; }
double wrapPi(double a);                 // into (-pi, pi]
double nearestTurn(double a, double ref);  // a + 2 pi k nearest to ref
bool finite(const Pose& x);
Eigen::Matrix3d rotZ(double a);
// Angle of the tool's x axis in the base XY plane (the planar orientation).
inline double planarAngle(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }
// Rotation vector of a rotation matrix (the log map), accurate near 0 and pi.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R);

}  // namespace stc::motion::kin

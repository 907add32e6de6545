// Kinematics and coordinate systems of an axis group (PLCopen Part 4 ACS /
// MCS / WCS / PCS / TCS; docs/motion-groups.md, "Coordinate systems").
//
//  - ACS: the members' own positions (axis units; degrees for rotary joints).
//  - MCS: the tool position of the group's kinematics (MC_SetKinTransform):
//    X, Y, Z and the orientation A, B, C in degrees, R = Rz(A) Ry(B) Rx(C);
//    members beyond the kinematics' joints are additional axes (coordinates 6..8).
//  - WCS: the world; MC_SetCoordinateTransform places MCS, PCS_1 and PCS_2 in it.
//  - PCS_1 / PCS_2: product frames, static or (MC_SetDynCoordTransform) fixed to
//    the tool of a master group, so that moves in them follow that group.
// A group without kinematics has the members as its coordinates in every system;
// frames then move the first three members as a point (X, Y, Z).
//
// This header keeps Eigen out: frames are plain arrays, the models sit behind
// GroupKinematics (stdlib-motion/kinematics).
#pragma once

#include <cstdint>
#include <memory>

namespace stc::motion {

class Kernel;
class AxisGroup;

// SMC_COORD_SYSTEM
enum class CoordSystem : uint8_t { ACS = 0, MCS = 1, WCS = 2, PCS1 = 3, PCS2 = 4, TCS = 5 };
bool validCoordSystem(int cs);

// A rigid frame: maps coordinates in the frame to coordinates in its parent
// (x_parent = R x + p).  R is row-major.
struct Frame {
  double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double p[3] = {0, 0, 0};

  // From X, Y, Z, A, B, C (degrees, R = Rz(A) Ry(B) Rx(C)); false when not finite or
  // beyond the plausible range (core/InputBounds.h).
  static bool fromCoords(const double* xyzabc, Frame& out);
  // X, Y, Z, A, B, C; the angles in (-180, 180], each shifted by whole turns to the value
  // nearest to nearAbc (when given).
  void toCoords(double* xyzabc, const double* nearAbc = nullptr) const;
  Frame operator*(const Frame& o) const;   // this after o: x -> this(o(x))
  Frame inverse() const;
  void point(const double* in, double* out) const;    // R in + p
  void vector(const double* in, double* out) const;   // R in
};

// The kinematic models a group can take (the TRAFO.Kin_* blocks of the ST face).
enum class KinModel : uint8_t { Gantry2, Gantry3, Scara2Z, TripodRotary, TripodLinear, Scara3Z, Articulated6 };
// Parameters by model (lengths in the axes' units, angles in degrees):
//   Gantry2/3:     [0..2] offsets X, Y, Z (axis = coordinate + offset)
//   Scara2Z:       [0] arm 1, [1] arm 2, [2..4] offsets of a0, a1 (degrees), a2 (Z)
//   TripodRotary:  [0] outer (base) radius, [1] inner (plate) radius, [2] upper arm, [3] rod,
//                  [4] rotation of arm A about Z, [5..7] offsets of a0..a2 (degrees)
//   TripodLinear:  [0] outer (rail) radius, [1] inner (plate) radius, [2] rod, [3] rail angle,
//                  [4] rotation of rail A about Z, [5..7] offsets of a0..a2
//   Scara3Z:       [0..2] arms 1..3, [3..5] offsets of a0..a2 (degrees), [6] of a3 (Z); the
//                  tool's direction in XY is A (a0 + a1 + a2)
//   Articulated6:  D-H lengths [0] d1, [1] a1, [2] a2, [3] d3, [4] a3, [5] d4, [6] d6 (the
//                  manual's CODESYS table: alpha 90, 0, 90, 90, -90, 0; theta offset 90 on
//                  joint 1), [7..12] offsets of a0..a5 (degrees)
struct KinSpec {
  KinModel model = KinModel::Gantry3;
  double param[16] = {};
};

// TRAFO.CONFIGDATA: branch choices of the inverse (+1 / -1; 0 reads as +1).
struct KinConfigData {
  int elbow = 1, shoulder = 1, wrist = 1;
};

class GroupKinematics {
public:
  // Null when the parameters are rejected (not finite, implausible, no valid geometry).
  static std::shared_ptr<const GroupKinematics> make(const KinSpec& spec);
  ~GroupKinematics();

  const KinSpec& spec() const;
  int joints() const;
  // Bit i set: Cartesian coordinate i (X, Y, Z, A, B, C) is set by the model; the others
  // are 0 in forward() and ignored by inverse().
  unsigned controlled() const;
  // q: joint positions in axis units (degrees for revolute joints, offsets included);
  // x: X..C of the tool in MCS.  False when there is no such pose.
  bool forward(const double* q, double* x) const;
  bool inverse(const double* x, const KinConfigData& c, const double* qNear, double* q) const;
  KinConfigData configOf(const double* q) const;

  struct Impl;

private:
  explicit GroupKinematics(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// ---- conversions of a group's positions (coordinate vectors of kMaxGroupAxes values)
//
// Coordinates in a Cartesian system: with kinematics X..C then the additional axes (6..8);
// without, the members themselves.  Frames are evaluated now (a dynamic PCS from its
// master group's set position).

// The frame of Cartesian system cs (MCS, WCS, PCS_1, PCS_2) in WCS; false when a dynamic
// PCS's master is gone or has no pose.
bool frameInWorld(const Kernel& k, const AxisGroup& g, CoordSystem cs, Frame& out);
// Members' positions q -> coordinates in cs (ACS: a copy; TCS: refused).
bool coordsOf(const Kernel& k, const AxisGroup& g, CoordSystem cs, const double* q, double* x);
// Coordinates in cs -> members' positions (inverse kinematics with config c, the revolute
// joints nearest to qNear).  False when unreachable.
bool jointsOf(const Kernel& k, const AxisGroup& g, CoordSystem cs, const double* x, const KinConfigData& c, const double* qNear,
              double* q);
// Coordinates in `from` -> coordinates in `to` (both Cartesian); nearAbc keeps the angles continuous.
bool convertCoords(const Kernel& k, const AxisGroup& g, CoordSystem from, CoordSystem to, const double* x, double* out);
// The number of coordinates of cs for g (ACS or no kinematics: the members; else 6 + additional axes).
int coordCount(const AxisGroup& g, CoordSystem cs);
// Is cs a Cartesian system of the group's kinematics (not ACS, and g has kinematics)?
bool cartesian(const AxisGroup& g, CoordSystem cs);

}  // namespace stc::motion

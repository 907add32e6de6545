// The G-code decoder's output: one path element per travel command, modelled
// on SoftMotion's SMC_GEOINFO (docs/cnc.md, "Elements").
//
// Positions are machine coordinates (the decoder has applied G54..G56 offsets,
// G91 increments and G98/G99 centres), so an element needs no context: the
// pipeline behind the decoder (tool correction, smoothing, the interpolator)
// reads elements one by one, as SMC_OUTQUEUE consumers do.
//
// An Element is a value of fixed size (no pointers, no allocation); queues copy
// it.
#pragma once

#include <array>
#include <cstdint>

namespace stc::cnc {

// The axes a program addresses, in SMC_POSINFO order: the interpolated X/Y/Z,
// the S-profile additional axes A/B/C and the linear additional axes P..W.
enum Axis : uint8_t { AxX, AxY, AxZ, AxA, AxB, AxC, AxP, AxQ, AxU, AxV, AxW, kAxisCount };
using Pos = std::array<double, kAxisCount>;
using Vec3 = std::array<double, 3>;
// The axis letter ('X' for AxX ...).
char axisLetter(Axis a);

// Element types.  The numbers follow the G code that makes the element where
// there is one; only MCommand = 120 is documented for SMC_MOVTYP (docs/cnc.md).
enum class MoveType : uint8_t {
  Lin = 1,        // G1 line
  Clw = 2,        // G2 arc or helix, clockwise about the plane normal
  Cclw = 3,       // G3 counter-clockwise
  Spline = 5,     // G5 (2D) / G10 (3D) cubic Hermite piece
  Parabola = 6,   // G6
  EllClw = 8,     // G8 elliptic arc
  EllCclw = 9,    // G9
  LinPos = 100,   // G0 positioning
  InitPos = 110,  // G92 set position (a jump of the position, no motion)
  MCommand = 120, // M function: stop and wait for the acknowledgement
  Dwell = 121,    // G4
  Sync = 122,     // G75: the decoder waits for the interpolator
};
const char* toString(MoveType t);
// TRUE for the types that move along a geometric path (G1/G2/G3/G5/G6/G8/G9/G10):
// the "tool path elements" whose tangents splines join.
bool isToolPath(MoveType t);
// TRUE for every type with a start and an end point that may differ (tool
// path elements and G0).
bool isMotion(MoveType t);

// The active plane of arcs: G17, G18, G19, or G16 with a normal I/J/K.
enum class Plane : uint8_t { XY, ZX, YZ, Free };
const char* toString(Plane p);

// Mark bits (SMC_GEOINFO's internal mark): set on the first motion element
// after the G code.  Bits 0-2 and 6-7 are SoftMotion's; 3-5 are ours.
enum Mark : uint16_t {
  MarkToolCorrEnd = 1u << 0,    // G40
  MarkToolCorrLeft = 1u << 1,   // G41
  MarkToolCorrRight = 1u << 2,  // G42
  MarkSmoothEnd = 1u << 3,      // G50
  MarkSmoothStart = 1u << 4,    // G51
  MarkRoundStart = 1u << 5,     // G52
  MarkLoopAvoidEnd = 1u << 6,   // G60
  MarkLoopAvoidStart = 1u << 7, // G61
  // Set by SMC_CheckVelocities once the element's end velocity (velEnd) is final;
  // the interpolator takes only elements that carry it (docs/cnc.md).
  MarkVelChecked = 1u << 8,
  // Set by SMC_PreAcknowledgeM on an MCommand (or the G75 Sync) element: the
  // interpolator passes it without stopping, and SMC_CheckVelocities computes the
  // junction of the motion elements around it as if it were not there.
  MarkMPreAcknowledged = 1u << 9,
};

enum class ToolSide : uint8_t { Off, Left, Right };       // G40 / G41 / G42
enum class Smoothing : uint8_t { Off, Smooth, Round };    // G50 / G51 / G52

// One H switch point on a motion element.
struct SwitchPoint {
  int16_t sw = 0;          // +n: switch n on, -n: switch n off (n = 1..32767)
  bool relative = false;   // TRUE: pos is the fraction O (0..1) of the element
  double pos = 0;          // L: distance from the start (>= 0) or from the end (< 0)
};
constexpr int kMaxSwitches = 8;   // per block

// Geometry of the element types (which one is valid follows from `type`).
struct ArcGeo {            // Clw / Cclw
  Vec3 centre;             // in the plane through the start point
  Vec3 u, v, normal;       // plane basis: u x v = normal
  double radius;
  double startAngle;       // rad, of the start point from u towards v
  double sweep;            // rad, > 0 counter-clockwise about `normal`, < 0 clockwise
  double rise;             // helix: end - start along `normal`
};
struct EllipseGeo {        // EllClw / EllCclw (XY plane)
  Vec3 centre;
  Vec3 major;              // unit vector of the main axis (K)
  double a, b;             // semi-axis along `major`, semi-axis across
  double majorAngle;       // rad, of `major` from +X
  double startPhi;         // rad, eccentric anomaly of the start point
  double sweepPhi;         // rad, > 0 counter-clockwise
  double rise;             // Z change (linear in the parameter)
};
struct SplineGeo {         // Spline: p(u) = h00 p0 + h10 c t0 + h01 p1 + h11 c t1
  Vec3 t0, t1;             // unit tangents at the start and the end
  double chord;            // c: the tangent magnitude at both ends; the decoder's pieces use the
                           // chord length, SMC_SmoothPath's corner splines 3 x the cut distance
  uint8_t dims;            // 2 (G5: X/Y, Z linear in u) or 3 (G10: X/Y/Z)
};
struct ParabolaGeo {       // Parabola: quadratic Bezier in X/Y, Z linear
  Vec3 vertex;             // where the tangent is parallel to the chord (u = 1/2)
  Vec3 control;            // Bezier control point: 2 vertex - (start + end) / 2
};

struct Element {
  int32_t objNo = 0;             // 1-based, in output order (iObjNo)
  int32_t line = 0;              // 1-based source line (iSourceLine_No is this - 1)
  int32_t column = 0;            // 1-based column of the block's command word
  int32_t blockNo = -1;          // N, -1 if the block has none (diSentenceNo)
  MoveType type = MoveType::Lin;
  Plane plane = Plane::XY;
  uint16_t marks = 0;            // Mark bits
  uint16_t axesUsed = 0;         // bit per Axis programmed so far (wAuxData-like)
  Pos start{}, end{};            // machine coordinates
  double vel = 0, acc = 0, dec = 0;   // F, E, E- (G0: FF, EF, EF- when set); 0 = never programmed
  double velEnd = 0;             // velocity allowed at the end (the junction to the next element):
                                 // written by SMC_CheckVelocities (dVelEnd), 0 from the decoder
  double s = 0;                  // S word (modal), stored as given
  double length = 0;             // path length over X/Y/Z (over all axes if X/Y/Z stay)
  // Preprocessing state in force for this element (modal).
  ToolSide toolSide = ToolSide::Off;
  Smoothing smoothing = Smoothing::Off;
  bool loopAvoid = false;
  double toolRadius = 0;         // D of G41/G42
  double smoothDist = 0;         // D of G51/G52
  union {
    ArcGeo arc;
    EllipseGeo ellipse;
    SplineGeo spline;
    ParabolaGeo parabola;
  };
  // MCommand: the M number and its parameters; Sync carries m = 65534 (the
  // reserved number SMC_PreAcknowledgeM's iM = -2 refers to).
  uint16_t m = 0;
  double k = 0, l = 0;
  double dwell = 0;              // Dwell: seconds
  uint8_t switchCount = 0;
  SwitchPoint switches[kMaxSwitches]{};

  Element() : arc{} {}
};

}  // namespace stc::cnc

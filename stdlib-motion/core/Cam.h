// Cam tables (vendor-free): the slave position as a function of the master
// position, y(x) on [xStart, xEnd], with its first and second derivatives.
//   XYVA      points (x, y, y', y''); between two points a 5th-order polynomial that
//             matches position, slope and curvature at both ends (continuous up to
//             acceleration).  Derivatives are per master unit: at master velocity vm
//             the slave moves at y'·vm and accelerates at y''·vm² + y'·am.
//   Table1D   slave values at equidistant master positions, linear in between.
//   Table2D   (x, y) pairs with increasing x, linear in between.
// Lookup is O(1) for Table1D and a binary search (O(log n)) otherwise.  Tappets
// are switch points stored with the cam.  Motion laws (VDI 2143) generate XYVA
// points.  The .CAM file format is in docs/motion-cam.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace stc::motion {

enum class CamKind : uint8_t { Table1D = 1, Table2D = 2, XYVA = 3 };

struct CamXYVA {
  double x = 0, y = 0, v = 0, a = 0;
};

enum class TappetAction : uint8_t { None = 0, On = 1, Off = 2, Invert = 3 };

// A switch point: the actions on group `group` when the master passes x forwards / backwards.
struct Tappet {
  double x = 0;
  int group = 1;                 // 1 .. kMaxTappetGroups
  TappetAction positive = TappetAction::None;
  TappetAction negative = TappetAction::None;
};
inline constexpr int kMaxTappetGroups = 512;   // MAX_NUM_TAPPETS
// By the names of the .CAM format and project.toml: "none", "on", "off", "invert".
bool tappetActionNamed(const std::string& name, TappetAction& out);
const char* tappetActionName(TappetAction a);
inline constexpr int kMaxCamElements = 65536;  // points of one cam (memory bound)

struct CamSample {
  double y = 0, dy = 0, ddy = 0;
};

// The extreme values of y, y' and y'' over the cam.
struct CamExtremes {
  double yMin = 0, yMax = 0, dyMin = 0, dyMax = 0, ddyMin = 0, ddyMax = 0;
};

class Cam {
public:
  // Builders: false with `error` on an invalid table (too few points, x not increasing,
  // non-finite or absurd values, bad tappets).
  static bool xyva(std::vector<CamXYVA> pts, std::vector<Tappet> tappets, Cam& out, std::string& error);
  static bool table1D(double xStart, double xEnd, std::vector<double> ys, std::vector<Tappet> tappets, Cam& out, std::string& error);
  static bool table2D(std::vector<std::array<double, 2>> pts, std::vector<Tappet> tappets, Cam& out, std::string& error);

  CamKind kind() const { return kind_; }
  double xStart() const { return x0_; }
  double xEnd() const { return x1_; }
  double length() const { return x1_ - x0_; }
  // The lift of one period: y(xEnd) - y(xStart) (a periodic cam adds it per period).
  double lift() const { return yEnd_ - yStart_; }
  // y, y', y'' at x (clamped to [xStart, xEnd]).
  CamSample at(double x) const;
  size_t segments() const { return seg_.size(); }
  const std::vector<Tappet>& tappets() const { return tappets_; }   // sorted by x
  const std::vector<CamXYVA>& points() const { return pts_; }       // as given (XYVA, 2-D: v = a = 0)
  const std::vector<double>& values() const { return ys_; }         // Table1D
  const CamExtremes& extremes() const { return ext_; }

private:
  struct Poly {   // y = c0 + t(c1 + t(c2 + ...)), t = x - segment start
    double c[6] = {};
  };
  bool finish(std::vector<Tappet> tappets, std::string& error);
  size_t segmentOf(double x) const;

  CamKind kind_ = CamKind::XYVA;
  double x0_ = 0, x1_ = 0, yStart_ = 0, yEnd_ = 0;
  double step_ = 0;                 // Table1D: the equidistant step
  std::vector<double> xs_;          // segment starts
  std::vector<Poly> seg_;
  std::vector<CamXYVA> pts_;
  std::vector<double> ys_;
  std::vector<Tappet> tappets_;
  CamExtremes ext_;
};

// Motion laws of VDI 2143 for a rise over u in [0, 1]: the normalised position s(u)
// (s(0) = 0, s(1) = 1) and its derivatives s'(u), s''(u).
enum class MotionLaw : uint8_t { Linear, Harmonic, Cycloid, ModifiedSine, ModifiedTrapezoid, Poly345 };
CamSample motionLaw(MotionLaw law, double u);
// By its project.toml / docs name: "linear", "harmonic", "cycloid", "modified_sine",
// "modified_trapezoid", "poly345"; false when unknown.
bool motionLawNamed(const std::string& name, MotionLaw& out);
// Appends the XYVA points of one segment from (x0, y0) to (x1, y1) under `law`
// (the point at x0 only when `pts` is empty).  The law rises on top of the base
// slope b: y = y0 + b·(x - x0) + (y1 - y0 - b·(x1 - x0))·s(u), so a segment joins
// neighbours that move at slope b (a synchronous zone) without a velocity step.
// Exact for Linear and Poly345; the other laws are sampled at 32 points (on their
// own joints), which keeps the quintic pieces within about 1e-9 of the law.
void appendMotionLaw(MotionLaw law, double x0, double x1, double y0, double y1, std::vector<CamXYVA>& pts, double baseSlope = 0);

// Tappets of one cam evaluated along the master's cam position.  A tappet fires
// its positive action when the position passes x forwards and its negative action
// when it passes backwards; after firing in one direction it fires again in that
// direction only once the position has been beyond x by more than the hysteresis
// on the other side (so a master that jitters around x switches once).
class TappetTracker {
public:
  // Group state: bits 0-1 the last ON/OFF (0 none, 1 on, 2 off), bit 2 the parity of
  // the INVERTs since; bit 3 set when the group has any action yet.
  using Groups = std::array<uint8_t, kMaxTappetGroups + 1>;   // by group id 1..512
  void reset(const std::vector<Tappet>& tappets, double x, double hysteresis);
  // The position moved from the last one to x within one period; false when nothing fired.
  bool move(double x);
  // The position jumped to x at a period boundary (no crossing; the arming restarts).
  void wrap(double x);
  const Groups& groups() const { return groups_; }
  static bool value(uint8_t state, bool initial) {
    const bool base = (state & 3) == 0 ? initial : (state & 3) == 1;
    return base != ((state & 4) != 0);
  }

private:
  void fire(const Tappet& t, TappetAction a);
  const std::vector<Tappet>* tappets_ = nullptr;
  std::vector<uint8_t> armed_;   // bit 0 positive, bit 1 negative
  double last_ = 0, h_ = 0;
  Groups groups_{};
};

// The .CAM text format (docs/motion-cam.md): write (XYVA, 1-D and 2-D) and read.
std::string writeCamText(const Cam& cam, const std::string& name);
enum class CamFileError : uint8_t { None, TooMuchData, WrongType, WrongVersion, UnexpectedEnd };
CamFileError readCamText(const std::string& text, Cam& out, std::string& name, std::string& detail);

}  // namespace stc::motion

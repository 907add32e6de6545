// Tool radius correction (G41/G42 ... G40) over decoded path elements: the core of
// SMC_ToolCorr (docs/cnc.md, "Tool radius correction").
//
// The corrector is streaming: push() the decoder's elements in order, take the
// corrected ones from the output (front/pop), call finish() after the last one.  It
// holds back the elements from the last contour element on until the next contour
// element arrives (the corner between the two decides where the first one ends);
// at most kMaxLookAhead elements without a contour move may come in between.
//
// Geometry: the contour elements (lines, G0 in the ramp modes, arcs and helices of
// the correction plane) are offset in the plane of the section (G17 XY, G18 ZX,
// G19 YZ) by the tool radius to the left (G41) or right (G42) of the direction of
// travel; the coordinate along the plane normal and the additional axes are not
// changed.  At an outside corner an arc of the tool radius about the programmed
// corner joins the two offset elements; at an inside corner both are cut at their
// intersection.  Elements that do not move in the plane (a Z plunge, M functions,
// dwells) go with the tool where it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

// SMC_TOOLCORRMODE: how the tool gets onto the offset path and off it again.
enum class ToolCorrMode : uint8_t {
  // A positioning element (G0) brings the tool from the programmed point to the offset
  // start of the first contour element; a G0 that already precedes it is moved there
  // instead.  At the end another positioning returns to the programmed point (or the
  // G0 that follows does).
  BlindPos = 0,
  // The first element goes from its programmed start straight to the offset start of
  // the second (no corner element there); the exit as TC_RAMP_IN.
  BlindIn = 1,
  // The first element keeps its programmed start and ends at its offset end, joined
  // to the next element by the corner rule; the first element after G40 starts at the
  // last offset end and ends at its programmed end (LinuxCNC's entry and exit).
  RampIn = 2,
};

enum class ToolCorrError : uint8_t {
  None,
  NotInPlane,          // a spline, parabola or ellipse under correction, an arc outside the
                       // correction plane, a plane change or G16 inside a section, G92 inside a section
  ArcSmallerThanTool,  // an arc whose offset radius would be <= 0 (concave arc smaller than the tool)
  LookAheadExceeded,   // more than kMaxLookAhead elements without a contour move inside a section
  BadRadius,           // a radius that is negative, not finite or above 1e9
};
const char* toString(ToolCorrError e);

class ToolCorrector {
public:
  static constexpr size_t kMaxLookAhead = 64;
  // Joins whose tangents turn by less than this (rad) are treated as tangent.
  static constexpr double kTangentTurn = 1e-9;

  explicit ToolCorrector(ToolCorrMode mode = ToolCorrMode::BlindPos, double defaultRadius = 0);

  // The radius of sections whose D is 0 (the block's dToolRadius); read when a section
  // starts.  Returns false (and changes nothing) for a bad value.
  bool setDefaultRadius(double r);
  ToolCorrMode mode() const { return mode_; }

  // Takes the next input element.  Returns false once an error has stopped the corrector
  // (the output keeps the elements corrected before it).
  bool push(const Element& e);
  // End of the input: the held elements are resolved, a section still open is closed.
  void finish();

  bool hasOutput() const { return !out_.empty(); }
  size_t outputSize() const { return out_.size(); }
  const Element& front() const { return out_.front(); }
  void pop() { out_.pop_front(); }
  // Input elements held back (not in the output yet).
  size_t held() const { return tail_.size() + (hasHeld_ ? 1 : 0); }

  ToolCorrError error() const { return error_; }
  int32_t errorLine() const { return errorLine_; }
  const std::string& errorMessage() const { return errorMessage_; }
  bool finished() const { return finished_; }

  // In-plane geometry of a contour element in the section's frame (public for the
  // implementation's helpers; not an interface).
  struct P2 {
    double x = 0, y = 0;
  };
  struct Piece {
    bool arc = false;
    P2 a, b;                 // start, end
    P2 c;                    // arc: centre
    double R = 0;            // arc: radius
    double angA = 0;         // arc: angle of the start about the centre
    double phi = 0;          // arc: sweep, > 0 counter-clockwise in the frame
  };

private:
  struct Held {
    Element orig;            // the programmed element
    Piece off;               // its offset geometry (start and end final only when emitted)
    Piece prog;              // its programmed geometry (the corner points, the tangents)
    bool rampIn = false;     // the entry element of TC_BLIND_IN / TC_RAMP_IN
  };

  void fail(ToolCorrError e, const Element& at, std::string message);
  void startSection(const Element& e, double radius);
  void closeSection(bool nextIsPositioning);
  void acceptContour(const Element& e);
  // Emits the held element (with its final end) and then the tail; lastG0Shift: the
  // in-plane shift of the positioning elements from the last G0 of the tail on.
  void emitHeld();
  void emitTail(const P2* lastG0Shift);
  void emitRampOut(const Element& e);
  void insertPositioning(const Element& like, const Pos& to);
  void emit(Element e);
  bool isContour(const Element& e) const;
  bool inPlaneStill(const Element& e) const;
  Piece pieceOf(const Element& e) const;
  P2 in(const Pos& p) const;
  void setIn(Pos& p, P2 q) const;
  Element elementOf(const Element& orig, const Piece& pc) const;

  ToolCorrMode mode_;
  double defaultRadius_;
  std::deque<Element> out_;
  std::vector<Element> tail_;  // held elements after the held contour element (or outside sections)
  Held held_;
  bool hasHeld_ = false;
  bool inSection_ = false;
  bool sectionHadContour_ = false;
  bool rampOutPending_ = false;
  double side_ = 1;            // +1 left (G41), -1 right (G42)
  double radius_ = 0;
  Plane plane_ = Plane::XY;
  int iu_ = AxX, iv_ = AxY, in_ = AxZ;
  Pos cur_{};                  // end of the last emitted element
  Element lastEmitted_;
  bool haveCur_ = false;
  Pos lastProgrammed_{};       // end of the last input element (the uncorrected position)
  ToolCorrError error_ = ToolCorrError::None;
  int32_t errorLine_ = 0;
  std::string errorMessage_;
  bool finished_ = false;
};

// One-shot correction of a decoded program (tests and tools).
std::vector<Element> correctAll(const std::vector<Element>& in, ToolCorrMode mode, double defaultRadius = 0,
                                ToolCorrError* error = nullptr);

}  // namespace stc::cnc

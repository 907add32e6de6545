// The program side of the Leadshine G-code blocks (ls_gcode.st): the text decoded a few
// lines per call (PreProcessGCodeNum), every element checked against what the block can
// run and capped by its limits, then given its end velocity by SMC_CheckVelocities' rule
// in a bounded window.  The block's interpolator takes the final elements from the front.
//
// Why a window and not a decoded vector: a 10,000-block file must not become 10,000
// elements in memory.  The decoder stops when the window is full and goes on when the
// interpolator has taken elements, so the memory is fixed whatever the program's length
// (the text itself, at most 64 MiB, and the decoder's index of block numbers aside).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/VelocityCheck.h"

namespace stc::motion::leadshine {

// What the block drives and the limits it puts on the program (latched at the Exec edge).
struct PathLimits {
  uint16_t drivenAxes = 0;        // bit per cnc::Axis the block has an axis for
  double vel = 0;                 // LimitVel: every driven axis' velocity
  double accDec = 0;              // LimitAccDec: every driven axis' acceleration and deceleration
  double arcAcc = 0;              // LimitMaxAcc: centripetal acceleration on arcs
  double arcJerk = 0;             // LimitMaxAccJerk: centripetal jerk on arcs (jerk-limited modes)
  bool jerkLimited = false;
  double cycle = 0.002;           // s, for the additional axes' velocity jump at junctions
  bool passMFunctions = false;    // no AcknM input: M functions are passed without stopping
};

class ProgramWindow {
public:
  static constexpr size_t kWindow = 32;   // decoded elements held ahead of the interpolator

  // `text` is copied; `name` is what diagnostics show (file:line:col).
  // `vars` resolves the program's $name$ (null: a $name$ is an error).
  ProgramWindow(std::string name, std::string text, const cnc::DecoderOptions& opts, const PathLimits& limits,
                std::unique_ptr<cnc::VariableAccess> vars);
  ProgramWindow(const ProgramWindow&) = delete;
  ProgramWindow& operator=(const ProgramWindow&) = delete;

  // Decodes up to `lines` program lines (comment and empty lines count) while the window
  // has room, and finalises the end velocities it can.  A G75 makes the decoder wait until
  // `pathEmpty` (the interpolator has run everything before it).  Diagnostics go to stderr.
  void pump(uint32_t lines, bool pathEmpty);

  bool hasFinal() const { return checked_ > 0; }
  const cnc::Element& front() const { return window_[head_]; }
  void pop();
  // Everything decoded and taken (the program has ended without error).
  bool ended() const { return error_ == 0 && decoder_->finished() && head_ == window_.size() && staging_.empty(); }
  // The SMC_ERROR number of the first problem (0: none); decoding stops there.
  int32_t error() const { return error_; }
  // The first problem was a $var$ the decoder could not replace.
  bool variableError() const { return variableError_; }

  // The line of the first element still in the window (0: none).
  int32_t nextLine() const { return head_ < window_.size() ? window_[head_].line : 0; }
  // The text of a 1-based program line without its line break (empty beyond the text).
  std::string_view lineText(int32_t line) const;

private:
  void admit();
  bool supported(const cnc::Element& e);
  void cap(cnc::Element& e) const;
  void fail(int32_t error);

  SourceManager sm_;
  DiagnosticsEngine diags_{sm_};
  uint32_t file_ = 0;
  PathLimits limits_;
  cnc::VelocityCheckOptions check_;
  std::unique_ptr<cnc::VariableAccess> vars_;   // before decoder_: it outlives it
  std::unique_ptr<cnc::Decoder> decoder_;
  cnc::ElementQueue staging_{8};     // the decoder's output before the checks
  std::vector<cnc::Element> window_;   // [head_, size): decoded, not taken; the first checked_ are final
  size_t head_ = 0, checked_ = 0;
  size_t printed_ = 0;
  bool waitSync_ = false;
  int32_t error_ = 0;
  bool variableError_ = false;
};

}  // namespace stc::motion::leadshine

// LsGCodePath.h: decoder -> block checks and limits -> end velocities, in a bounded window.
#include "stdlib-motion/leadshine/LsGCodePath.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/codesys_sm3/Sm3NcProgram.h"

namespace stc::motion::leadshine {

namespace {

constexpr int32_t kInvalidSyntax = 1204;      // SMC_DEC_INVALID_SYNTAX (the decoder's gcode-unsupported)
constexpr int32_t kCvNonPositive = 1100;      // SMC_CV_ACC_DEC_VEL_NONPOSITIVE

bool isArc(const cnc::Element& e) { return e.type == cnc::MoveType::Clw || e.type == cnc::MoveType::Cclw; }

}  // namespace

ProgramWindow::ProgramWindow(std::string name, std::string text, const cnc::DecoderOptions& opts, const PathLimits& limits,
                             std::unique_ptr<cnc::VariableAccess> vars)
    : limits_(limits), vars_(std::move(vars)) {
  file_ = sm_.addBuffer(std::move(name), std::move(text));
  decoder_ = std::make_unique<cnc::Decoder>(sm_, file_, diags_, opts, vars_.get());
  // The additional axes follow the path length: at a junction their velocity may jump; allow
  // what LimitAccDec changes in one cycle (SMC_CheckVelocities' bCheckAddAxVelJump).
  check_.checkAddAxVelJump = true;
  check_.maxAddAxVelDifference = limits.accDec * limits.cycle;
  window_.reserve(kWindow);
}

void ProgramWindow::fail(int32_t error) {
  if (error_ == 0) error_ = error;
}

// Elements the block cannot run as programmed are refused rather than run differently.
bool ProgramWindow::supported(const cnc::Element& e) {
  const char* why = nullptr;
  std::string axisMessage;
  const uint16_t foreign = static_cast<uint16_t>(e.axesUsed & ~limits_.drivenAxes & ~0x7u);
  if (foreign != 0) {
    int k = cnc::AxA;
    while (!(foreign & (1u << k))) ++k;
    axisMessage = std::string("the axis ") + cnc::axisLetter(static_cast<cnc::Axis>(k)) +
                  " is not one of this block's axes; its moves would be lost";
    why = axisMessage.c_str();
  } else if (e.toolSide != cnc::ToolSide::Off) {
    why = "tool radius correction (G41/G42) needs SMC_ToolCorr, which the Leadshine G-code blocks do not run";
  } else if (e.smoothing != cnc::Smoothing::Off) {
    why = "corner smoothing (G51/G52) needs SMC_SmoothPath, which the Leadshine G-code blocks do not run";
  } else if (e.loopAvoid) {
    why = "loop avoidance (G61) needs SMC_AvoidLoop, which the Leadshine G-code blocks do not run";
  }
  if (!why) return true;
  const uint32_t line = static_cast<uint32_t>(std::max(1, e.line));
  const uint32_t at = sm_.lineStart(file_, line) + static_cast<uint32_t>(std::max(0, e.column - 1));
  diags_.error(SourceLoc{file_, at}, why, "gcode-unsupported");
  fail(kInvalidSyntax);
  return false;
}

// LimitVel / LimitAccDec hold for every driven axis: X/Y/Z never move faster than the path,
// an additional axis moves |dk| / length times as fast.  On arcs the centripetal acceleration
// v^2 / r stays within LimitMaxAcc and, jerk-limited, the centripetal jerk v^3 / r^2 within
// LimitMaxAccJerk.
void ProgramWindow::cap(cnc::Element& e) const {
  if (!cnc::isMotion(e.type)) return;
  double ratio = 1;
  if (e.length > 0)
    for (int k = cnc::AxA; k < cnc::kAxisCount; ++k)
      if (limits_.drivenAxes & (1u << k)) ratio = std::max(ratio, std::fabs(e.end[k] - e.start[k]) / e.length);
  double vmax = limits_.vel / ratio;
  const double amax = limits_.accDec / ratio;
  if (isArc(e) && e.arc.radius > 0) {
    vmax = std::min(vmax, std::sqrt(limits_.arcAcc * e.arc.radius));
    if (limits_.jerkLimited) vmax = std::min(vmax, std::cbrt(limits_.arcJerk * e.arc.radius * e.arc.radius));
  }
  e.vel = std::min(e.vel, vmax);
  e.acc = std::min(e.acc, amax);
  e.dec = std::min(e.dec, amax);
}

// Moves decoded elements into the window while it has room.
void ProgramWindow::admit() {
  if (head_ > 0 && window_.size() == kWindow) {   // make room at the back
    window_.erase(window_.begin(), window_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
  while (!staging_.empty() && window_.size() < kWindow && error_ == 0) {
    cnc::Element e = staging_.front();
    staging_.pop();
    if (!supported(e)) break;
    cap(e);
    if (e.type == cnc::MoveType::MCommand && limits_.passMFunctions) e.marks |= cnc::MarkMPreAcknowledged;
    window_.push_back(e);
  }
}

void ProgramWindow::pump(uint32_t lines, bool pathEmpty) {
  uint32_t budget = lines;
  while (error_ == 0) {
    admit();
    if (!staging_.empty() || error_ != 0) break;   // the window is full: the interpolator first
    if (decoder_->finished()) break;
    if (waitSync_) {
      if (head_ < window_.size() || !pathEmpty) break;   // G75: until the path has caught up
      waitSync_ = false;
    }
    if (budget == 0) break;
    const cnc::StepResult r = decoder_->step(staging_, budget);
    budget -= std::min(budget, r.blocks);
    sm3face::printNewDiagnostics(diags_, printed_);
    if (decoder_->errorCount() > 0) {
      for (const Diagnostic& d : diags_.diagnostics())
        if (d.severity == Severity::Error) {
          variableError_ = d.code == "gcode-variable";
          break;
        }
      fail(static_cast<int32_t>(decoder_->firstError()));
      break;
    }
    if (r.status == cnc::StepStatus::Sync) waitSync_ = true;
    if (r.blocks == 0 && r.elements == 0 && r.status == cnc::StepStatus::Progress) break;
  }
  sm3face::printNewDiagnostics(diags_, printed_);
  if (error_ != 0) return;
  // End velocities of what follows the final elements (SMC_CheckVelocities in place).
  std::span<cnc::Element> pending(window_.data() + head_ + checked_, window_.size() - head_ - checked_);
  const bool endOfList = decoder_->finished() && staging_.empty();
  const bool cannotGrow = window_.size() == kWindow && checked_ == 0;
  const cnc::VelocityCheckResult r = cnc::checkVelocities(pending, endOfList, cannotGrow, check_);
  checked_ += r.finalized;
  if (r.error) fail(kCvNonPositive);
}

void ProgramWindow::pop() {
  ++head_;
  --checked_;
  if (head_ == window_.size()) {
    window_.clear();
    head_ = 0;
  }
}

std::string_view ProgramWindow::lineText(int32_t line) const {
  if (line <= 0 || static_cast<unsigned>(line) > sm_.lineCount(file_)) return {};
  std::string_view text = sm_.lineText(SourceLoc{file_, sm_.lineStart(file_, static_cast<unsigned>(line))});
  while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.remove_suffix(1);
  return text;
}

}  // namespace stc::motion::leadshine

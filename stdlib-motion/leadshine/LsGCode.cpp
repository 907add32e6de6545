// The Leadshine G-code blocks (ls_gcode.st; docs/leadshine-interpolation.md, "G-code
// blocks"): LS_3AxisGCode ... LS_6AxisGCodeAxisUVW_File.  The manual describes them as
// wrappers of the SoftMotion CNC pipeline, and that is what a run is here:
//
//  - the program (an SMC_CNC_REF or a file of the data directory) is decoded a few lines per
//    call and velocity-checked in a bounded window (LsGCodePath.h);
//  - stdlib-motion/cnc's Interpolator (the core of SMC_Interpolator: M functions, dwell, H
//    switches, single steps, holds, override) makes one set position per call;
//  - every axis follows its coordinate of that position (plus the block's offset) in the same
//    cycle through a position follow command, as SMC_ControlAxisByPos does; the path starts
//    where the axes stand, so there is never a gap.
//
// The run's state lives on the block's kernel slot (FbBehaviour), found again through the
// instance's __handle; it holds no pointer into ST memory.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>

#include "stdlib-motion/cnc/Interpolator.h"
#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/codesys_sm3/Sm3NcProgram.h"
#include "stdlib-motion/core/InputBounds.h"
#include "stdlib-motion/core/Profiles.h"
#include "stdlib-motion/leadshine/LsGCodePath.h"
#include "stdlib-motion/leadshine/LsMoves.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;
using namespace stc::motion::leadshine;

namespace {

constexpr int32_t kNoCncRef = 1500;       // SMC_NO_CNC_REF_TYPE
constexpr int32_t kFileMissing = 2000;    // SMC_RNCF_FILE_DOESNT_EXIST
constexpr int32_t kFileTooBig = 2002;     // SMC_RNCF_BUFFER_TOO_SMALL
constexpr int32_t kNotVarList = 2005;     // SMC_RNCF_NOT_VARLIST
constexpr size_t kMaxAxes = 6;
constexpr double kMaxOffset = 1e10;       // the decoder's bound of a position after offsets

// The inputs of one call, whichever block it is.
struct GInputs {
  bool exec = false, halt = false, stop = false;
  bool singleStep = false, waitAtNextStop = false, acknM = false;
  bool hasAcknM = false;                  // the 6-axis block: M functions wait for AcknM
  uint32_t ipoCycleUs = 0;
  int preProcessNum = 0;
  int velocityMode = 1;
  double jerk = 0, limitVel = 0, limitAccDec = 0, limitMaxAcc = 0, limitMaxAccJerk = 0;
  bool hasRatio = false;
  double velRatio = 1;
  bool hasDefaults = false;               // the _File blocks: F/E/E- and FF/EF/EF- defaults
  double defVel = 0, defAcc = 0, defDec = 0, defVelFF = 0, defAccFF = 0, defDecFF = 0;
  double offset[kMaxAxes] = {};
};

// Where the program text comes from: an SMC_CNC_REF, or a file name.
struct ProgramSource {
  const sm3::SMC_CNC_REF* ref = nullptr;
  bool fromFile = false;
  std::string fileName;
  const void* varList = nullptr;     // SMC_VarList_0 (the 6-axis block)
};

enum class Phase : uint8_t { Idle, Running, Stopping, Ending };

// The state of one block instance, kept on its kernel slot.
class GCodeRun : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}

  uint64_t axisSlot[kMaxAxes] = {};       // the follow commands, one per axis (handles)
  Axis* axis[kMaxAxes] = {};              // the axes of the run (kernel axes live as long as the kernel)
  bool owned[kMaxAxes] = {};              // the axis still follows the path
  double lastSet[kMaxAxes] = {};          // the set position written last
  double offset[kMaxAxes] = {};
  size_t axes = 0;
  std::array<stc::cnc::Axis, kMaxAxes> coord{};   // the program coordinate of each axis

  std::unique_ptr<ProgramWindow> program;
  std::unique_ptr<stc::cnc::Interpolator> ipo;
  Phase phase = Phase::Idle;
  bool endAsDone = false;                 // Ending: Done (else CommandAborted or the error below)
  int32_t endError = 0;
  int preProcessNum = 1;
  bool fedAny = false;                    // an element went to the interpolator
  double quickDecel = 0;                  // Stop: LimitAccDec
  double velRatio = 1;

  // Lines of the elements handed to the interpolator, not finished yet (front: in control).
  int32_t inFlight[stc::cnc::Interpolator::kMaxInFlight] = {};
  int flightHead = 0, flightCount = 0;
  int32_t lastFinished = 0, beforeLastFinished = 0;

  // outputs (PLCopen hold rules: Done / CommandAborted / Error held while Exec, else one cycle)
  bool exec = false;
  bool done = false, aborted = false, error = false;
  int32_t errorId = 0;
  uint64_t terminalCycle = 0;
  bool readError = false, decodeError = false, exportError = false;
  double vel = 0;
  uint32_t switches = 0;
  int16_t lastSwitch = 0;
  uint16_t m = 0;
  int32_t shownLines[3] = {-1, -1, -1};   // the lines whose text GCodeTextArr holds
  bool terminal() const { return done || aborted || error; }
};

void publishNothing(void*, const FbOutputs&) {}

template <class T>
FbSlot& axisSlot(T* self, GCodeRun& r, size_t i) {
  return kernel().slot(r.axisSlot[i], self, FbKind::Follow, &publishNothing);
}

// ---- inputs

bool usableDefault(double v, double bound) { return std::isfinite(v) && v >= 0 && v <= bound; }

int32_t checkInputs(const GInputs& in, size_t axes, const CallCtx& c) {
  if (in.ipoCycleUs == 0 || static_cast<int64_t>(in.ipoCycleUs) * 1000 != c.intervalNs) return kIpoParaErr;
  if (in.preProcessNum <= 0) return kIpoParaErr;
  if (in.velocityMode != 0 && in.velocityMode != 1 && in.velocityMode != 3) return kIpoParaErr;
  if (!bounds::jerk(in.jerk) || in.jerk == 0) return kIpoParaErr;
  if (!bounds::velocity(in.limitVel) || !bounds::rate(in.limitAccDec) || !bounds::rate(in.limitMaxAcc)) return kIpoParaErr;
  if (!bounds::jerk(in.limitMaxAccJerk) || in.limitMaxAccJerk == 0) return kIpoParaErr;
  if (in.hasRatio && !(in.velRatio >= 0.01 && in.velRatio <= 2)) return kIpoParaErr;
  for (size_t i = 0; i < axes; ++i)
    if (!std::isfinite(in.offset[i]) || std::fabs(in.offset[i]) > kMaxOffset) return kIpoParaErr;
  if (in.hasDefaults) {
    if (!bounds::velocity(in.defVel) || !bounds::velocity(in.defVelFF)) return kIpoVel;
    if (!bounds::rate(in.defAcc) || !bounds::rate(in.defAccFF)) return kIpoAcc;
    if (!bounds::rate(in.defDec) || !bounds::rate(in.defDecFF)) return kIpoDec;
  }
  return 0;
}

// An axis given twice or an encoder: -15; not powered and standing, or a member of an enabled
// group of an AXIS_GROUP_REF (or of another LS block that moves): -17.
int32_t checkAxes(Kernel& k, Axis* const* axes, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < i; ++j)
      if (axes[i] == axes[j]) return kIpoConfigAxisErr;
    if (axes[i]->config().drive.kind == AxisKind::Encoder) return kIpoConfigAxisErr;
  }
  for (size_t i = 0; i < n; ++i) {
    if (!axes[i]->ready() || axes[i]->state() != AxisState::Standstill) return kIpoAxisNotStandStill;
    for (size_t g = 0; g < k.groupCount(); ++g) {
      const AxisGroup* grp = k.group(static_cast<uint32_t>(g));
      if (grp && grp->enabled() && !grp->internal && grp->identOf(*axes[i]) >= 0) return kIpoAxisNotStandStill;
    }
  }
  return 0;
}

// The program's text and decoder options; 0 or the block's error.
int32_t loadProgram(const ProgramSource& src, const GInputs& in, std::string& name, std::string& text,
                    stc::cnc::DecoderOptions& o, std::unique_ptr<NcVariables>& vars) {
  MotionSession& s = MotionSession::current();
  if (src.varList && !usableVarList(s, src.varList)) return kNotVarList;
  if (src.fromFile) {
    vars = std::make_unique<NcVariables>(s, src.varList);
    uint64_t size = 0;
    switch (readNcFile(s, src.fileName, kMaxNcProgramBytes, text, size)) {
    case NcFileRead::Ok: break;
    case NcFileRead::Missing: return kFileMissing;
    case NcFileRead::TooBig: return kFileTooBig;
    }
    name = src.fileName;
    o.requireBlockNumbers = true;   // the manual: every block of a file has its N
    o.defaultVel = in.defVel;
    o.defaultAcc = in.defAcc;
    o.defaultDec = in.defDec;
    o.defaultRapidVel = in.defVelFF;
    o.defaultRapidAcc = in.defAccFF;
    o.defaultRapidDec = in.defDecFF;
    return 0;
  }
  const sm3::SMC_CNC_REF* p = src.ref;
  if (!usableCncRef(s, p)) return kNoCncRef;
  if (p->pvl && !usableVarList(s, p->pvl)) return kNotVarList;
  vars = std::make_unique<NcVariables>(s, p->pvl);
  // The program's defaults: 0 is "not set" (then LimitVel / LimitAccDec; G0 uses F / E / E-).
  if (!usableDefault(p->fDefaultVel, bounds::kVelocity) || !usableDefault(p->fDefaultVelFF, bounds::kVelocity)) return kIpoVel;
  if (!usableDefault(p->fDefaultAccel, bounds::kRate) || !usableDefault(p->fDefaultAccelFF, bounds::kRate)) return kIpoAcc;
  if (!usableDefault(p->fDefaultDecel, bounds::kRate) || !usableDefault(p->fDefaultDecelFF, bounds::kRate)) return kIpoDec;
  text.assign(reinterpret_cast<const char*>(p->pText), p->dwTextSize);
  name.assign(p->strFileName, strnlen(p->strFileName, sizeof p->strFileName));
  if (name.empty()) name = "CNC_Ref";
  o.defaultVel = p->fDefaultVel > 0 ? p->fDefaultVel : in.limitVel;
  o.defaultAcc = p->fDefaultAccel > 0 ? p->fDefaultAccel : in.limitAccDec;
  o.defaultDec = p->fDefaultDecel > 0 ? p->fDefaultDecel : in.limitAccDec;
  o.defaultRapidVel = p->fDefaultVelFF;
  o.defaultRapidAcc = p->fDefaultAccelFF;
  o.defaultRapidDec = p->fDefaultDecelFF;
  return 0;
}

// ---- the run

void finishRun(GCodeRun& r, bool done, bool aborted, int32_t errorId, const CallCtx& c) {
  r.phase = Phase::Idle;
  r.done = done;
  r.aborted = aborted;
  r.error = errorId != 0;
  r.errorId = errorId;
  r.terminalCycle = c.cycle;
  r.program.reset();
  r.ipo.reset();
  r.vel = 0;
  r.m = 0;
}

// Ends the follow commands of the axes still following: they stand at their last set position
// (applied in the previous cycle's step) and are free for the next command.
template <class T>
void releaseAxes(T* self, GCodeRun& r, const CallCtx& c) {
  Kernel& k = kernel();
  for (size_t i = 0; i < r.axes; ++i) {
    if (!r.owned[i]) continue;
    r.owned[i] = false;
    FbSlot& fb = axisSlot(self, r, i);
    Axis& ax = *r.axis[i];
    callFollow(k, fb, ax, false, false, FollowInputs{}, c);
    if (fb.out.busy && ax.controller == &fb) {
      k.finish(fb, &c, c.cycle, false, false, Error::None);
      if (ax.state() == AxisState::SynchronizedMotion) ax.setState(AxisState::Standstill);
    }
  }
}

// The path stops (Stop, a lost axis, an error): quick stop along the path with LimitAccDec;
// the outcome is reported once the path stands.
void beginStop(GCodeRun& r, int32_t errorId) {
  if (r.phase != Phase::Running) return;
  r.phase = Phase::Stopping;
  r.endAsDone = false;
  r.endError = errorId;
}

void noteProgramError(GCodeRun& r) {
  r.readError = r.program->variableError();
  r.decodeError = !r.readError;
  beginStop(r, r.program->error());
}

// An axis taken by another command (CommandAborted) or in an error (the error) stops the path;
// the other axes follow it to rest.
template <class T>
void watchAxes(T* self, GCodeRun& r) {
  for (size_t i = 0; i < r.axes; ++i) {
    if (!r.owned[i]) continue;
    const FbSlot& fb = axisSlot(self, r, i);
    if (fb.out.busy && !fb.out.terminal()) continue;
    r.owned[i] = false;
    const int32_t e = fb.out.error ? static_cast<int32_t>(smcError(fb.out.errorId)) : 0;
    if (r.phase == Phase::Running) beginStop(r, e);
    else if (e != 0 && r.endError == 0) r.endError = e;
  }
}

void popFinished(GCodeRun& r) {
  for (int n = r.ipo->takeFinished(); n > 0 && r.flightCount > 0; --n) {
    r.beforeLastFinished = r.lastFinished;
    r.lastFinished = r.inFlight[r.flightHead];
    r.flightHead = (r.flightHead + 1) % stc::cnc::Interpolator::kMaxInFlight;
    --r.flightCount;
  }
}

// Hands the final elements to the interpolator while it takes them.
void feed(GCodeRun& r) {
  ProgramWindow& p = *r.program;
  while (p.hasFinal() && r.ipo->wantsMore() && r.flightCount < stc::cnc::Interpolator::kMaxInFlight) {
    if (r.ipo->feed(p.front()) != stc::cnc::kIpoOk) return;
    r.fedAny = true;
    r.inFlight[(r.flightHead + r.flightCount) % stc::cnc::Interpolator::kMaxInFlight] = p.front().line;
    ++r.flightCount;
    p.pop();
  }
  if (p.ended()) r.ipo->endOfList();
}

// One cycle of the running path: program, interpolator, axes.
template <class T>
void cycleRun(T* self, GCodeRun& r, const GInputs& in, const CallCtx& c) {
  if (in.hasRatio && in.velRatio >= 0.01 && in.velRatio <= 2) r.velRatio = in.velRatio;   // online; a bad value is ignored
  if (r.phase == Phase::Running && in.stop) beginStop(r, 0);
  if (r.phase == Phase::Running) {
    r.program->pump(static_cast<uint32_t>(r.preProcessNum), r.ipo->inFlight() == 0);
    feed(r);
    if (r.program->error() != 0) {
      noteProgramError(r);
      if (!r.fedAny) {   // nothing has moved: the axes are free at once and the error shows now
        releaseAxes(self, r, c);
        return finishRun(r, false, false, r.endError, c);
      }
    }
  }
  stc::cnc::IpoControls ctl;
  ctl.slowStop = in.halt;
  ctl.quickStop = r.phase == Phase::Stopping;
  ctl.quickDecel = r.quickDecel;
  ctl.singleStep = in.singleStep;
  ctl.waitAtNextStop = in.waitAtNextStop;
  ctl.acknM = in.acknM;
  ctl.override = r.velRatio;
  const stc::cnc::IpoOutput& o = r.ipo->step(ctl);
  popFinished(r);
  if (r.phase == Phase::Running && r.ipo->error() != 0) beginStop(r, r.ipo->error());

  // Every axis takes its coordinate in this cycle's step; at rest with velocity 0, so it
  // stands exactly when the path stands.
  Kernel& k = kernel();
  const double dt = static_cast<double>(c.intervalNs) * 1e-9;
  for (size_t i = 0; i < r.axes; ++i) {
    if (!r.owned[i]) continue;
    const double p = o.pos[r.coord[i]] + r.offset[i];
    FollowInputs set;
    set.mask = kFollowPosition | kFollowVelocity;
    set.position = p;
    set.velocity = o.vel == 0 ? 0.0 : (p - r.lastSet[i]) / dt;
    r.lastSet[i] = p;
    callFollow(k, axisSlot(self, r, i), *r.axis[i], true, false, set, c);
  }
  r.vel = std::fabs(o.vel);
  r.switches = o.switches;
  r.lastSwitch = o.lastSwitch;
  r.m = o.m;
  if (r.phase == Phase::Running && o.finished) {
    r.phase = Phase::Ending;
    r.endAsDone = true;
  } else if (r.phase == Phase::Stopping && o.vel == 0) {
    r.phase = Phase::Ending;
  }
}

// The lines of the previous, current and next element and their text (the 6-axis block),
// while a program runs; they keep their last values when it has ended.
template <class T>
void showLines(T* self, GCodeRun& r) {
  if (!r.program) return;
  const bool flying = r.flightCount > 0;
  const int32_t current = flying ? r.inFlight[r.flightHead] : r.lastFinished;
  const int32_t previous = flying ? r.lastFinished : r.beforeLastFinished;
  int32_t next = 0;
  if (r.flightCount > 1) next = r.inFlight[(r.flightHead + 1) % stc::cnc::Interpolator::kMaxInFlight];
  else next = r.program->nextLine();
  if constexpr (requires { self->GCodeTextNoArr; }) {
    const int32_t lines[3] = {previous, current, next};
    for (int i = 0; i < 3; ++i) {
      self->GCodeTextNoArr[i] = lines[i];
      if (lines[i] == r.shownLines[i]) continue;
      r.shownLines[i] = lines[i];
      const std::string_view text = r.program->lineText(lines[i]);
      const size_t room = sizeof self->GCodeTextArr[i] - 1;
      const size_t len = std::min(text.size(), room);
      if (text.size() > room) r.exportError = true;
      std::memcpy(self->GCodeTextArr[i], text.data(), len);
      self->GCodeTextArr[i][len] = 0;
    }
  }
  self->LineCurrent = static_cast<int16_t>(std::clamp<int32_t>(current, 0, INT16_MAX));
}

template <class T>
void writeOutputs(T* self, GCodeRun& r, const GInputs& in) {
  self->Done = r.done;
  self->CommandAborted = r.aborted;
  self->Error = r.error;
  self->ErrorID = r.errorId;
  self->Busy = r.phase != Phase::Idle;
  self->CommandHalt = r.phase == Phase::Running && in.halt;
  self->Vel = r.phase != Phase::Idle ? r.vel : 0.0;
  self->dwSwitches = r.switches;
  showLines(self, r);
  if constexpr (requires { self->wM; }) {
    self->iLastSwitch = r.lastSwitch;
    self->wM = r.m;
    self->bExportGCodeTextErr = r.exportError;
    self->bReadNCFileError = r.readError;
    self->bNCFileDecodeError = r.decodeError;
  }
}

template <class T>
ProgramSource sourceOf(const T* s) {
  ProgramSource src;
  if constexpr (requires { s->CNC_FileName; }) {
    src.fromFile = true;
    src.fileName.assign(s->CNC_FileName, strnlen(s->CNC_FileName, sizeof s->CNC_FileName));
    if constexpr (requires { s->SMC_VarList_0; }) src.varList = &s->SMC_VarList_0;
  } else {
    src.ref = static_cast<const sm3::SMC_CNC_REF*>(s->CNC_Ref);   // POINTER TO: an untyped address
  }
  return src;
}

// The Exec edge: checks, the program, the follow commands, and the first cycle of the path.
template <class T, size_t N>
void startRun(T* self, GCodeRun& r, Axis* const (&axes)[N], const stc::cnc::Axis (&coords)[N], const GInputs& in,
              const CallCtx& c) {
  r.done = r.aborted = r.error = false;
  r.errorId = 0;
  r.readError = r.decodeError = r.exportError = false;
  r.switches = 0;
  r.lastSwitch = 0;
  r.m = 0;
  r.flightHead = r.flightCount = 0;
  r.fedAny = false;
  r.lastFinished = r.beforeLastFinished = 0;
  self->LineCurrent = 0;
  if constexpr (requires { self->GCodeTextNoArr; }) {
    for (int i = 0; i < 3; ++i) {
      self->GCodeTextNoArr[i] = 0;
      self->GCodeTextArr[i][0] = 0;
      r.shownLines[i] = 0;
    }
  }
  auto fail = [&](int32_t e) { finishRun(r, false, false, e, c); };
  Kernel& k = kernel();
  if (int32_t e = checkInputs(in, N, c); e != 0) return fail(e);
  if (int32_t e = checkAxes(k, axes, N); e != 0) return fail(e);
  if (in.stop) return finishRun(r, false, true, 0, c);   // Stop already TRUE: nothing moves

  std::string name, text;
  stc::cnc::DecoderOptions opts;
  std::unique_ptr<NcVariables> vars;
  if (int32_t e = loadProgram(sourceOf(self), in, name, text, opts, vars); e != 0) {
    r.decodeError = e == kFileMissing || e == kFileTooBig;
    r.readError = e == kNotVarList;
    return fail(e);
  }
  opts.stopAtFirstError = true;
  for (size_t i = 0; i < N; ++i) opts.startPosition[coords[i]] = axes[i]->set().p - in.offset[i];
  PathLimits lim;
  for (stc::cnc::Axis a : coords) lim.drivenAxes = static_cast<uint16_t>(lim.drivenAxes | (1u << a));
  lim.vel = in.limitVel;
  lim.accDec = in.limitAccDec;
  lim.arcAcc = in.limitMaxAcc;
  lim.arcJerk = in.limitMaxAccJerk;
  lim.jerkLimited = in.velocityMode != 0;
  lim.cycle = in.ipoCycleUs * 1e-6;
  lim.passMFunctions = !in.hasAcknM;
  stc::cnc::IpoSettings cfg;
  cfg.cycle = lim.cycle;
  cfg.mode = in.velocityMode == 0 ? stc::cnc::VelMode::Trapezoid
             : in.velocityMode == 1 ? stc::cnc::VelMode::Sigmoid
                                    : stc::cnc::VelMode::Quadratic;
  cfg.jerk = in.jerk;
  int16_t ipoError = 0;
  auto ipo = std::make_unique<stc::cnc::Interpolator>(cfg, ipoError);
  if (ipoError != 0) return fail(ipoError);
  r.program = std::make_unique<ProgramWindow>(std::move(name), std::move(text), opts, lim, std::move(vars));
  r.ipo = std::move(ipo);

  // Each axis: a follow command holding it where it stands (it becomes the command in control).
  r.axes = N;
  for (size_t i = 0; i < N; ++i) {
    r.axis[i] = axes[i];
    r.coord[i] = coords[i];
    r.offset[i] = in.offset[i];
    r.lastSet[i] = axes[i]->set().p;
    FbSlot& fb = axisSlot(self, r, i);
    fb.execute = false;   // a new command on this slot
    FollowInputs hold;
    hold.mask = kFollowPosition | kFollowVelocity;
    hold.position = r.lastSet[i];
    callFollow(k, fb, *axes[i], true, false, hold, c);
    r.owned[i] = fb.out.busy;
    if (!fb.out.busy) {
      releaseAxes(self, r, c);
      return fail(kIpoAxisNotStandStill);
    }
  }
  r.phase = Phase::Running;
  r.preProcessNum = in.preProcessNum;
  r.quickDecel = in.limitAccDec;
  r.velRatio = in.hasRatio ? in.velRatio : 1.0;
  cycleRun(self, r, in, c);
}

template <class T, size_t N>
void gcodeBody(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], const stc::cnc::Axis (&coords)[N], const GInputs& in) {
  const CallCtx c = callContext();
  Axis* axes[N];
  for (size_t i = 0; i < N; ++i) {
    axes[i] = bind(refs[i], c);
    if (!axes[i]) {   // an axis of another task (or none)
      self->Error = true;
      self->Busy = false;
      self->ErrorID = static_cast<int32_t>(smcError(Error::NotReadyForMotion));
      return;
    }
  }
  FbSlot& main = kernel().slot(self->__handle, self, FbKind::Leadshine, &publishNothing);
  main.lastCallCycle = c.cycle;
  GCodeRun& r = behaviourOf<GCodeRun>(main);
  const bool rising = in.exec && !r.exec;
  r.exec = in.exec;
  if (!in.exec && r.terminal() && c.cycle > r.terminalCycle) {
    r.done = r.aborted = r.error = false;
    r.errorId = 0;
  }
  if (r.phase == Phase::Ending) {   // the axes stood still in the last step: report
    releaseAxes(self, r, c);
    finishRun(r, r.endAsDone, !r.endAsDone && r.endError == 0, r.endAsDone ? 0 : r.endError, c);
  } else if (r.phase != Phase::Idle) {
    watchAxes(self, r);
    bool anyOwned = false;
    for (size_t i = 0; i < r.axes; ++i) anyOwned = anyOwned || r.owned[i];
    if (!anyOwned) finishRun(r, false, r.endError == 0, r.endError, c);   // nothing left to stop
    else cycleRun(self, r, in, c);
  }
  if (rising && r.phase == Phase::Idle) startRun(self, r, axes, coords, in, c);   // an edge while running is ignored
  writeOutputs(self, r, in);
  for (Axis* ax : axes) mirrorCall(*ax);
}

// ---- the blocks

template <class T>
GInputs inputsOf(const T* s) {
  GInputs in;
  in.exec = s->Exec;
  in.halt = s->Halt;
  in.stop = s->Stop;
  in.ipoCycleUs = s->IpoCycle;
  in.preProcessNum = s->PreProcessGCodeNum;
  in.velocityMode = s->VelocityMode;
  in.jerk = s->Jerk;
  in.limitVel = s->LimitVel;
  in.limitAccDec = s->LimitAccDec;
  in.limitMaxAcc = s->LimitMaxAcc;
  in.limitMaxAccJerk = s->LimitMaxAccJerk;
  if constexpr (requires { s->VelRatio; }) {
    in.hasRatio = true;
    in.velRatio = s->VelRatio;
  }
  if constexpr (requires { s->DefaultVel; }) {
    in.hasDefaults = true;
    in.defVel = s->DefaultVel;
    in.defAcc = s->DefaultAcc;
    in.defDec = s->DefaultDec;
    in.defVelFF = s->DefaultVelFF;
    in.defAccFF = s->DefaultAccFF;
    in.defDecFF = s->DefaultDecFF;
  }
  if constexpr (requires { s->AcknM; }) {
    in.hasAcknM = true;
    in.singleStep = s->SingleStep;
    in.waitAtNextStop = s->WaitAtNextStop;
    in.acknM = s->AcknM;
    const double off[kMaxAxes] = {s->dOffsetX, s->dOffsetY, s->dOffsetZ, s->dOffsetU, s->dOffsetV, s->dOffsetW};
    std::copy(std::begin(off), std::end(off), in.offset);
  }
  return in;
}

template <class T, size_t N>
void gcodeBlock(T* self, sm3::AXIS_REF_SM3* const (&refs)[N], const stc::cnc::Axis (&coords)[N]) {
  gcodeBody(self, refs, coords, inputsOf(self));
}

using stc::cnc::AxP;
using stc::cnc::AxU;
using stc::cnc::AxV;
using stc::cnc::AxW;
using stc::cnc::AxX;
using stc::cnc::AxY;
using stc::cnc::AxZ;
constexpr stc::cnc::Axis kXYZ[] = {AxX, AxY, AxZ};
constexpr stc::cnc::Axis kXYZU[] = {AxX, AxY, AxZ, AxU};
constexpr stc::cnc::Axis kXYZP[] = {AxX, AxY, AxZ, AxP};
constexpr stc::cnc::Axis kXYZUVW[] = {AxX, AxY, AxZ, AxU, AxV, AxW};

#define LS_GCODE_3(fn) \
  void fn(sm3::fn* self) { gcodeBlock(self, {self->AxisX, self->AxisY, self->AxisZ}, kXYZ); }
#define LS_GCODE_4(fn, fourth, coords) \
  void fn(sm3::fn* self) { gcodeBlock(self, {self->AxisX, self->AxisY, self->AxisZ, self->fourth}, coords); }

LS_GCODE_3(LS_3AxisGCode)
LS_GCODE_3(LS_3AxisGCode_File)
LS_GCODE_4(LS_4AxisGCode, AxisU, kXYZU)
LS_GCODE_4(LS_4AxisGCode_File, AxisU, kXYZU)
LS_GCODE_4(LS_4AxisGCodeAxisP, AxisP, kXYZP)
LS_GCODE_4(LS_4AxisGCodeAxisP_File, AxisP, kXYZP)

void LS_6AxisGCodeAxisUVW_File(sm3::LS_6AxisGCodeAxisUVW_File* self) {
  gcodeBlock(self, {self->AxisX, self->AxisY, self->AxisZ, self->AxisU, self->AxisV, self->AxisW}, kXYZUVW);
}

}  // namespace

namespace stc::motion {

void registerLsGCodeNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(LS_3AxisGCode, LS_3AxisGCode)
  STC_SM3_NATIVE(LS_3AxisGCode_File, LS_3AxisGCode_File)
  STC_SM3_NATIVE(LS_4AxisGCode, LS_4AxisGCode)
  STC_SM3_NATIVE(LS_4AxisGCode_File, LS_4AxisGCode_File)
  STC_SM3_NATIVE(LS_4AxisGCodeAxisP, LS_4AxisGCodeAxisP)
  STC_SM3_NATIVE(LS_4AxisGCodeAxisP_File, LS_4AxisGCodeAxisP_File)
  STC_SM3_NATIVE(LS_6AxisGCodeAxisUVW_File, LS_6AxisGCodeAxisUVW_File)
}

}  // namespace stc::motion

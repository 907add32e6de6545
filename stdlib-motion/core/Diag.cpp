// Diagnostic FBs: limits, in-position, maxima, tracking error, distance,
// communication, FB errors and the axis diagnostic log.  docs/motion-diag.md.
#include "stdlib-motion/core/Diag.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>

namespace stc::motion::diag {

namespace {

bool finiteNonNegative(double x) { return std::isfinite(x) && x >= 0; }
int64_t toNs(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }

// State of the Enable-type monitors, kept in the slot between calls.
class Monitor : public FbBehaviour {
public:
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // never in control of the axis
  bool enabled = false;
  double max = 0;
  uint32_t timeAtMax = 0;
  int64_t insideSinceNs = -1, timeoutFromNs = 0;
  bool inPosition = false;
  std::deque<double> setHistory;    // set positions of the latest calls (tracking error dead time)
};

Monitor& monitor(FbSlot& fb) {
  if (!fb.behaviour) fb.behaviour = std::make_unique<Monitor>();
  return static_cast<Monitor&>(*fb.behaviour);
}

// Records v as the new maximum if |v| exceeds it.
void track(Monitor& m, double v, uint32_t stamp) {
  if (std::fabs(v) > std::fabs(m.max)) {
    m.max = v;
    m.timeAtMax = stamp;
  }
}

}  // namespace

double signedAcceleration(const Kinematic& k) {
  return k.a * k.v >= 0 ? std::fabs(k.a) : -std::fabs(k.a);
}

CheckLimitsOut checkLimits(const Axis& ax, bool enable, bool checkVel, bool checkAccDec, const SwMax& lim) {
  CheckLimitsOut o;
  if (!enable) return o;
  if ((checkVel && !finiteNonNegative(lim.velocity)) ||
      (checkAccDec && (!finiteNonNegative(lim.acceleration) || !finiteNonNegative(lim.deceleration)))) {
    o.error = true;
    o.errorId = kBadInput;
    return o;
  }
  o.busy = true;
  const Kinematic& s = ax.set();
  if (checkVel && std::fabs(s.v) > lim.velocity) o.exceeded = true;
  if (checkAccDec) {
    const double a = signedAcceleration(s);
    if (a > 0 && a > lim.acceleration) o.exceeded = true;
    if (a < 0 && -a > lim.deceleration) o.exceeded = true;
  }
  return o;
}

InPositionOut callInPosition(FbSlot& fb, const Axis* ax, const InPositionIn& in, const CallCtx& c) {
  Monitor& m = monitor(fb);
  InPositionOut o;
  if (!in.enable || !ax) {
    m.enabled = m.inPosition = false;
    return o;
  }
  if (!std::isfinite(in.window) || in.window <= 0 || !finiteNonNegative(in.posTime) || !finiteNonNegative(in.timeOut)) {
    m.enabled = m.inPosition = false;
    o.error = true;
    o.errorId = kBadInput;
    return o;
  }
  if (!m.enabled) {   // rising edge: the time-out runs from here
    m.enabled = true;
    m.inPosition = false;
    m.insideSinceNs = -1;
    m.timeoutFromNs = c.nowNs;
  }
  o.busy = true;
  o.distance = std::fabs(ax->set().p - ax->actPosition());
  if (o.distance < in.window) {
    if (m.insideSinceNs < 0) m.insideSinceNs = c.nowNs;
    if (c.nowNs - m.insideSinceNs >= toNs(in.posTime)) m.inPosition = true;
  } else {
    if (m.inPosition) m.timeoutFromNs = c.nowNs;   // left the window: a new time-out starts
    m.inPosition = false;
    m.insideSinceNs = -1;
  }
  o.inPosition = m.inPosition;
  o.timeOut = !m.inPosition && in.timeOut > 0 && c.nowNs - m.timeoutFromNs >= toNs(in.timeOut);
  return o;
}

MaxOut callGetMax(FbSlot& fb, const Axis* ax, MaxOf what, bool enable, uint32_t timeStamp, bool resetMax) {
  Monitor& m = monitor(fb);
  MaxOut o;
  if (!enable || !ax) {
    m.enabled = false;
    o.max = m.max;
    o.timeAtMax = m.timeAtMax;
    return o;
  }
  if (!m.enabled || resetMax) {
    m.enabled = true;
    m.max = 0;
    m.timeAtMax = 0;
  }
  track(m, what == MaxOf::Velocity ? ax->set().v : signedAcceleration(ax->set()), timeStamp);
  o.busy = true;
  o.max = m.max;
  o.timeAtMax = m.timeAtMax;
  return o;
}

TrackingOut callTrackingError(FbSlot& fb, const Axis* ax, bool enable, uint8_t deadTimeCycles, uint32_t timeStamp, bool resetMax) {
  Monitor& m = monitor(fb);
  TrackingOut o;
  if (!enable || !ax) {
    m.enabled = false;
    m.setHistory.clear();
    o.max = m.max;
    o.timeAtMax = m.timeAtMax;
    return o;
  }
  if (!m.enabled || resetMax) {
    m.enabled = true;
    m.max = 0;
    m.timeAtMax = 0;
  }
  m.setHistory.push_back(ax->set().p);
  while (m.setHistory.size() > static_cast<size_t>(deadTimeCycles) + 1) m.setHistory.pop_front();
  // The set position deadTimeCycles calls ago (the oldest one while fewer are known).
  const double delayedSet = m.setHistory.front();
  const double e = delayedSet - ax->actPosition();
  o.actual = ax->set().v < 0 ? -e : e;   // + = lag behind the set point in the direction of motion
  track(m, o.actual, timeStamp);
  o.busy = true;
  o.max = m.max;
  o.timeAtMax = m.timeAtMax;
  return o;
}

MeasureOut callMeasureDistance(FbSlot& fb, Axis& ax, bool execute) {
  MeasureOut o;
  if (execute && !fb.execute) fb.target = ax.actPosition();   // rising edge: the start (unwrapped)
  fb.execute = execute;
  fb.axis = &ax;
  if (execute) fb.endVelocity = ax.actPosition() - fb.target;
  o.busy = execute;
  o.distance = fb.endVelocity;
  return o;
}

ComOut checkCommunication(const Axis& ax, bool enable) {
  ComOut o;
  if (!enable) return o;
  o.valid = true;
  o.operational = ax.drive().communication();
  o.state = o.operational ? ComState::Operational : ComState::Error;
  return o;
}

FbErrorOut readFbError(const Axis& ax, bool enable) {
  FbErrorOut o;
  if (!enable) return o;
  o.busy = true;
  o.record = ax.fbError;
  return o;
}

bool clearFbError(Axis& ax) {
  if (ax.state() == AxisState::ErrorStop) return false;
  ax.fbError = FbErrorRecord{};
  return true;
}

// ---------------------------------------------------------------- diagnostic log

namespace {

DiagnosticLog* logOf(FbSlot& fb) { return dynamic_cast<DiagnosticLog*>(fb.behaviour.get()); }

void appendNumber(std::string& s, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}

void stopObserving(Axis& ax, FbSlot& fb) {
  ax.observers.erase(std::remove(ax.observers.begin(), ax.observers.end(), &fb), ax.observers.end());
}

}  // namespace

DiagnosticLog::~DiagnosticLog() {
  if (file) std::fclose(file);
}

void callDiagnosticLog(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool closeFile, const LogConfig& cfg, const CallCtx& c) {
  const bool rising = k.beginExecute(fb, execute, c);
  fb.axis = &ax;
  if (!fb.behaviour) fb.behaviour = std::make_unique<DiagnosticLog>();
  DiagnosticLog& log = *logOf(fb);
  if (!fb.out.busy) stopObserving(ax, fb);
  if (rising && !fb.out.busy) {
    if (log.file) std::fclose(log.file);
    log.file = nullptr;
    log.buffer.clear();
    log.recording = log.closeRequested = log.fileOpen = log.closed = false;
    log.ioError = Error::None;
    if (ax.state() == AxisState::ErrorStop) return k.fail(fb, ax.error() != Error::None ? ax.error() : Error::NotReadyForMotion, c);
    if (cfg.fileName.empty()) return k.fail(fb, Error::AdlFileCannotBeOpened, c);
    log.cfg = cfg;
    log.recording = true;
    log.prevActVelocity = ax.actVelocity();
    log.havePrev = true;
    fb.sinceNs = c.nowNs - c.intervalNs;   // time of the latest step (the actual velocity above)
    fb.out.busy = true;
    if (std::find(ax.observers.begin(), ax.observers.end(), &fb) == ax.observers.end()) ax.observers.push_back(&fb);
    fb.sync();
  }
  if (fb.out.busy && closeFile && !log.closeRequested) {
    log.closeRequested = true;
    log.recording = false;
    fb.sync();
  }
}

void DiagnosticLog::afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t nowNs, uint64_t cycle) {
  // (Observers are removed in the next call, never during the kernel's loop over them.)
  if (!fb.out.busy) return;
  if (ioError != Error::None || closed) {
    const Error e = ioError;
    recording = false;
    if (file) std::fclose(file);
    file = nullptr;
    k.finish(fb, nullptr, cycle, e == Error::None, false, e);
    return;
  }
  if (!recording) return;
  const double dt = static_cast<double>(nowNs - fb.sinceNs) * 1e-9;
  const double actAcc = dt > 0 ? (ax.actVelocity() - prevActVelocity) / dt : 0;
  prevActVelocity = ax.actVelocity();
  fb.sinceNs = nowNs;
  std::string rec;
  bool first = true;
  auto field = [&](bool on, double v) {
    if (!on) return;
    if (!first) rec += cfg.separator;
    first = false;
    appendNumber(rec, v);
  };
  field(cfg.setPosition, ax.reportPosition(ax.set().p));
  field(cfg.actPosition, ax.reportPosition(ax.actPosition()));
  field(cfg.setVelocity, ax.set().v);
  field(cfg.actVelocity, ax.actVelocity());
  field(cfg.setAcceleration, ax.set().a);
  field(cfg.actAcceleration, actAcc);
  rec += cfg.recordEnd;
  if (buffer.size() + rec.size() > kBufferSize) {
    recording = false;
    if (file) std::fclose(file);
    file = nullptr;
    k.finish(fb, nullptr, cycle, false, false, Error::AdlBufferOverrun);
    return;
  }
  buffer += rec;
}

void writeToFile(FbSlot& fb) {
  DiagnosticLog* log = logOf(fb);
  if (!log || !fb.out.busy || log->closed || log->ioError != Error::None) return;
  const bool write = log->cfg.mode == LogMode::Continuous || log->closeRequested;
  if (!write) return;
  if (!log->fileOpen) {
    log->file = log->cfg.open ? log->cfg.open() : std::fopen(log->cfg.fileName.c_str(), "wb");
    if (!log->file) {
      log->ioError = Error::AdlFileCannotBeOpened;
      log->recording = false;
      return;
    }
    log->fileOpen = true;
  }
  if (!log->buffer.empty() && std::fwrite(log->buffer.data(), 1, log->buffer.size(), log->file) != log->buffer.size()) {
    log->ioError = Error::AdlFileCannotBeOpened;
    log->recording = false;
    return;
  }
  log->buffer.clear();
  std::fflush(log->file);
  if (log->closeRequested) {
    std::fclose(log->file);
    log->file = nullptr;
    log->closed = true;
  }
}

}  // namespace stc::motion::diag

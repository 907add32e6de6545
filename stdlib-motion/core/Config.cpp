// Parameter access and axis configuration (see Config.h, docs/motion-config.md).
#include "stdlib-motion/core/Config.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace stc::motion {

// ---------------------------------------------------------------- axis parameters

namespace {

constexpr AxisParamInfo kParams[] = {
    // PLCopen Part 1 numbers (Leadshine table: 2, 3, 9, 13, 15, 16 alias the 1000+ numbers).
    {1, ParamType::Real, false, "CommandedPosition"},
    {2, ParamType::Real, true, "fSWLimitPositive"},
    {3, ParamType::Real, true, "fSWLimitNegative"},
    {4, ParamType::Bool, true, "bSWLimitEnable"},      // EnableLimitPos: SM3 has one enable for both limits
    {5, ParamType::Bool, true, "bSWLimitEnable"},      // EnableLimitNeg
    {6, ParamType::Bool, false, "EnablePosLagMonitoring"},
    {7, ParamType::Real, true, "MaxPositionLag"},
    {8, ParamType::Real, false, "MaxVelocitySystem"},
    {9, ParamType::Real, true, "fMaxVelocity"},
    {10, ParamType::Real, false, "ActualVelocity"},
    {11, ParamType::Real, false, "CommandedVelocity"},
    {12, ParamType::Real, false, "MaxAccelerationSystem"},
    {13, ParamType::Real, true, "fMaxAcceleration"},
    {14, ParamType::Real, false, "MaxDecelerationSystem"},
    {15, ParamType::Real, true, "fMaxDeceleration"},
    {16, ParamType::Real, true, "fMaxJerk"},
    // SoftMotion AXIS_REF_SM3 numbers.
    {1000, ParamType::Int, false, "nAxisState"},
    {1010, ParamType::Bool, false, "bRegulatorOn"},
    {1011, ParamType::Bool, false, "bDriveStart"},
    {1012, ParamType::Bool, false, "bCommunication"},
    {1013, ParamType::Int, false, "wCommunicationState"},
    {1014, ParamType::Int, false, "uiDriveInterfaceError"},
    {1015, ParamType::Bool, false, "bRegulatorRealState"},
    {1016, ParamType::Bool, false, "bDriveStartRealState"},
    {1025, ParamType::Real, false, "fTaskCycle"},
    {1030, ParamType::Bool, false, "bError"},
    {1031, ParamType::Int, false, "dwErrorID"},
    {1036, ParamType::Bool, false, "bDisableErrorLogging"},
    {1040, ParamType::Bool, false, "bVirtual"},
    {1060, ParamType::Int, false, "iMovementType"},
    {1061, ParamType::Real, true, "fPositionPeriod"},
    {1062, ParamType::Int, false, "eRampType"},
    {1112, ParamType::Real, true, "fMaxVelocity"},
    {1122, ParamType::Real, true, "fMaxAcceleration"},
    {1132, ParamType::Real, true, "fMaxDeceleration"},
    {1142, ParamType::Real, true, "fMaxJerk"},
    {1152, ParamType::Real, false, "fMaxCurrent"},
    {1153, ParamType::Real, false, "fSWMaxCurrent"},
    {1162, ParamType::Real, false, "fMaxTorque"},
    {1200, ParamType::Real, true, "fSWLimitPositive"},
    {1201, ParamType::Real, true, "fSWLimitNegative"},
    {1203, ParamType::Real, true, "fSWLimitDeceleration"},
    {1205, ParamType::Bool, true, "bSWLimitEnable"},
    {1250, ParamType::Real, true, "fSWErrorMaxDistance"},
};

bool standstillOrPowerOff(const Axis& ax) {
  return ax.state() == AxisState::Standstill || ax.state() == AxisState::PowerOff;
}

bool finiteNonNegative(double x) { return std::isfinite(x) && x >= 0; }

}  // namespace

const AxisParamInfo* axisParameter(int32_t number) {
  for (const AxisParamInfo& p : kParams)
    if (p.number == number) return &p;
  return nullptr;
}

Error readAxisParameter(const Axis& ax, int32_t number, double& v, int64_t intervalNs) {
  const AxisConfig& c = ax.config();
  const Drive& d = ax.drive();
  switch (number) {
    case 1: v = ax.reportPosition(ax.set().p); break;
    case 2: case 1200: v = c.swLimitPositive; break;
    case 3: case 1201: v = c.swLimitNegative; break;
    case 4: case 5: case 1205: v = c.swLimitEnable; break;
    case 6: v = c.drive.followingErrorLimit > 0; break;
    case 7: v = c.drive.followingErrorLimit; break;
    case 8: case 9: case 1112: v = c.maxVelocity; break;
    case 10: v = ax.actVelocity(); break;
    case 11: v = ax.set().v; break;
    case 12: case 13: case 1122: v = c.maxAcceleration; break;
    case 14: case 15: case 1132: v = c.maxDeceleration; break;
    case 16: case 1142: v = c.maxJerk; break;
    case 1000: v = static_cast<double>(ax.state()); break;
    case 1010: v = ax.powerRequested(); break;
    case 1011: v = ax.driveStart(); break;
    case 1012: v = d.communication(); break;
    case 1013: v = d.communication() ? 100 : 0; break;
    case 1014: v = d.errorCode(); break;
    case 1015: v = ax.operational(); break;
    case 1016: v = ax.operational() && ax.driveStart(); break;
    case 1025: v = static_cast<double>(intervalNs) * 1e-9; break;
    case 1030: v = ax.state() == AxisState::ErrorStop; break;
    // 1031 (the axis error number) is answered by the face: the core's faults have no numbers.
    case 1036: v = 0; break;        // no error log is kept: logging is never disabled
    case 1040: v = c.drive.kind == AxisKind::Virtual; break;
    case 1060: v = ax.isModulo() ? 0 : 1; break;
    case 1061: v = c.period; break;
    case 1062: v = static_cast<double>(c.ramp); break;
    case 1152: v = 100; break;      // the motor model has no current or torque limit:
    case 1153: v = 0; break;        // these report the documented defaults
    case 1162: v = 0; break;
    case 1203: v = c.swLimitDeceleration; break;
    case 1250: v = c.swErrorMaxDistance; break;
    default: return Error::ReadParamUnknown;
  }
  return Error::None;
}

Error writeAxisParameter(Axis& ax, int32_t number, double v) {
  const AxisParamInfo* p = axisParameter(number);
  if (!p || !p->writable) return Error::WriteParamInvalid;
  if (!std::isfinite(v)) return Error::WriteParamConversionError;
  if (p->type == ParamType::Bool && v != 0 && v != 1) return Error::WriteParamConversionError;
  AxisConfig& c = ax.mutableConfig();
  switch (number) {
    case 2: case 1200: c.swLimitPositive = v; break;
    case 3: case 1201: c.swLimitNegative = v; break;
    case 4: case 5: case 1205: c.swLimitEnable = v != 0; break;
    case 7:
      if (v < 0) return Error::WriteParamInvalid;
      c.drive.followingErrorLimit = v;
      ax.drive().mutableConfig().followingErrorLimit = v;
      break;
    case 9: case 1112: case 13: case 1122: case 15: case 1132: case 16: case 1142: {
      if (v < 0) return Error::WriteParamInvalid;   // 0: not checked
      double& target = number == 9 || number == 1112    ? c.maxVelocity
                       : number == 13 || number == 1122 ? c.maxAcceleration
                       : number == 15 || number == 1132 ? c.maxDeceleration
                                                        : c.maxJerk;
      target = v;
      break;
    }
    case 1061:
      // The period of a modulo axis, in standstill or power_off (SMC_SetMovementType for the type).
      if (!ax.isModulo() || v <= 0 || !standstillOrPowerOff(ax)) return Error::WriteParamInvalid;
      setPositionPeriod(ax, v);
      break;
    case 1203:
      if (v < 0) return Error::WriteParamInvalid;
      c.swLimitDeceleration = v;
      break;
    case 1250:
      if (v < 0) return Error::WriteParamInvalid;
      c.swErrorMaxDistance = v;
      break;
    default: return Error::WriteParamInvalid;
  }
  return Error::None;
}

// ---------------------------------------------------------------- SDO

namespace {

// Size and signedness of the objects the simulated drive serves (appendix 2 of the AMC1600C manual).
struct ObjectType { uint16_t index; uint8_t sub; uint8_t length; bool isSigned; };
constexpr ObjectType kObjectTypes[] = {
    {0x603F, 0, 2, false}, {0x6040, 0, 2, false}, {0x6041, 0, 2, false}, {0x6060, 0, 1, true},
    {0x6061, 0, 1, true},  {0x6064, 0, 4, true},  {0x6065, 0, 4, false}, {0x6067, 0, 2, false},
    {0x6068, 0, 2, false}, {0x606C, 0, 4, true},  {0x606D, 0, 4, false}, {0x606E, 0, 2, false},
    {0x6071, 0, 2, true},  {0x6072, 0, 2, false}, {0x6077, 0, 2, true},  {0x607A, 0, 4, true},
    {0x607C, 0, 4, true},  {0x607D, 1, 4, true},  {0x607D, 2, 4, true},  {0x607E, 0, 1, false},
    {0x607F, 0, 4, false}, {0x6081, 0, 4, false}, {0x6083, 0, 4, false}, {0x6084, 0, 4, false},
    {0x6085, 0, 4, false}, {0x6086, 0, 2, true},  {0x6087, 0, 4, false}, {0x6091, 1, 4, false},
    {0x6091, 2, 4, false}, {0x6098, 0, 1, true},  {0x6099, 1, 4, false}, {0x6099, 2, 4, false},
    {0x609A, 0, 4, false}, {0x60B0, 0, 4, true},  {0x60B1, 0, 4, true},  {0x60B2, 0, 2, true},
    {0x60E0, 0, 2, false}, {0x60E1, 0, 2, false}, {0x60E6, 0, 1, false}, {0x60FD, 0, 4, false},
    {0x60FE, 1, 4, false}, {0x60FF, 0, 4, true},  {0x6502, 0, 4, false},
};

// The object's size and signedness; objects not in the table take the size the request names.
ObjectType typeOf(const SdoAddress& a) {
  for (const ObjectType& t : kObjectTypes)
    if (t.index == a.index && t.sub == a.sub) return t;
  return ObjectType{a.index, a.sub, a.length, true};
}

}  // namespace

int32_t sdoParameterNumber(uint8_t length, uint16_t index, uint8_t sub) {
  const uint32_t raw = (static_cast<uint32_t>(length) << 24) | (static_cast<uint32_t>(index) << 8) | sub;
  return -static_cast<int32_t>(raw);
}

bool decodeSdo(int32_t number, SdoAddress& a) {
  if (number >= 0) return false;
  const uint32_t raw = static_cast<uint32_t>(-static_cast<int64_t>(number));
  a.length = static_cast<uint8_t>(raw >> 24);
  a.index = static_cast<uint16_t>((raw >> 8) & 0xFFFF);
  a.sub = static_cast<uint8_t>(raw & 0xFF);
  return a.length == 1 || a.length == 2 || a.length == 4;
}

Error sdoRead(const Axis& ax, const SdoAddress& a, double& value) {
  if (!ax.drive().communication()) return Error::ReadParamRequestingError;
  const ObjectType t = typeOf(a);
  int64_t raw = 0;
  if (t.length != a.length || !ax.drive().readObject(a.index, a.sub, raw)) return Error::ReadParamRequestingError;
  value = static_cast<double>(raw);
  return Error::None;
}

Error sdoWrite(Axis& ax, const SdoAddress& a, double value) {
  const ObjectType t = typeOf(a);
  const double bits = 8.0 * a.length;
  const double lo = t.isSigned ? -std::ldexp(1.0, static_cast<int>(bits) - 1) : 0.0;
  const double hi = t.isSigned ? std::ldexp(1.0, static_cast<int>(bits) - 1) - 1 : std::ldexp(1.0, static_cast<int>(bits)) - 1;
  if (!std::isfinite(value) || value != std::trunc(value) || value < lo || value > hi) return Error::WriteParamConversionError;
  if (!ax.drive().communication()) return Error::WriteParamSendingError;
  if (t.length != a.length || !ax.drive().writeObject(a.index, a.sub, static_cast<int64_t>(value)))
    return Error::WriteParamSendingError;
  return Error::None;
}

// ---------------------------------------------------------------- FB state

namespace {

// The core side of the parameter and configuration FBs: reader state and a
// transfer (SDO, gearing change) that waits for the kernel step of the cycle.
class ConfigBehaviour : public FbBehaviour {
public:
  ParameterState state;
  bool pending = false;
  bool hasNumber = false;
  int32_t number = 0;
  bool asBool = false;
  std::function<void(Kernel&, FbSlot&, Axis&, uint64_t)> transfer;

  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}   // never in control of the axis
  void afterStep(Kernel& k, FbSlot& fb, Axis& ax, int64_t, uint64_t cycle) override {
    if (!pending) return;
    pending = false;
    if (transfer) transfer(k, fb, ax, cycle);
  }
};

ConfigBehaviour& behaviourOf(FbSlot& fb) {
  if (auto* b = dynamic_cast<ConfigBehaviour*>(fb.behaviour.get())) return *b;
  fb.behaviour = std::make_unique<ConfigBehaviour>();
  return static_cast<ConfigBehaviour&>(*fb.behaviour);
}

// The kernel walks Axis::observers by index while stepping; slots are only
// added or removed here, in FB calls.
void observe(Axis& ax, FbSlot& fb) {
  if (std::find(ax.observers.begin(), ax.observers.end(), &fb) == ax.observers.end()) ax.observers.push_back(&fb);
}
void unobserve(Axis& ax, FbSlot& fb) {
  ax.observers.erase(std::remove(ax.observers.begin(), ax.observers.end(), &fb), ax.observers.end());
}

// Start of every Execute-type call: false if nothing is to be done (no rising edge).
bool edge(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const CallCtx& c) {
  ConfigBehaviour& b = behaviourOf(fb);
  if (!b.pending) unobserve(ax, fb);
  if (!k.beginExecute(fb, execute, c)) {
    fb.sync();
    return false;
  }
  fb.axis = &ax;
  return true;
}

void done(Kernel& k, FbSlot& fb, const CallCtx& c) { k.finish(fb, &c, c.cycle, true, false, Error::None); }

}  // namespace

const ParameterState& parameterState(const FbSlot& fb) {
  static const ParameterState none;
  if (auto* b = dynamic_cast<const ConfigBehaviour*>(fb.behaviour.get())) return b->state;
  return none;
}

// ---------------------------------------------------------------- parameter FBs

void callReadParameter(Kernel& k, FbSlot& fb, Axis& ax, bool enable, int32_t number, bool asBool, const CallCtx& c,
                       const FaceParameters* face) {
  ConfigBehaviour& b = behaviourOf(fb);
  fb.lastCallCycle = c.cycle;
  fb.callSeq = ++k.callCounter;
  fb.axis = &ax;
  fb.execute = enable;
  if (!enable) {
    // Enable FALSE: every output resets (Leadshine: "all outputs FALSE/0").
    b.pending = false;
    b.hasNumber = false;
    unobserve(ax, fb);
    fb.out = FbOutputs{};
    b.state = ParameterState{};
    fb.sync();
    return;
  }
  if (!b.hasNumber || b.number != number || b.asBool != asBool) {
    // A new parameter: the previous value and error no longer apply.
    b.state.valid = false;
    fb.out.error = false;
    fb.out.errorId = Error::None;
  }
  b.hasNumber = true;
  b.number = number;
  b.asBool = asBool;
  SdoAddress a;
  if (number < 0 && decodeSdo(number, a)) {
    // One SDO request per call, answered in the bus exchange of this cycle.
    b.pending = true;
    b.transfer = [a, asBool](Kernel&, FbSlot& f, Axis& x, uint64_t) {
      ConfigBehaviour& s = behaviourOf(f);
      double v = 0;
      const Error e = sdoRead(x, a, v);
      f.out.error = e != Error::None;
      f.out.errorId = e;
      f.out.busy = e == Error::None;
      s.state.valid = e == Error::None;
      if (e == Error::None) s.state.value = asBool ? (v != 0 ? 1.0 : 0.0) : v;
      f.sync();
    };
    observe(ax, fb);
    fb.out.busy = !fb.out.error;
    fb.sync();
    return;
  }
  b.pending = false;
  unobserve(ax, fb);
  double v = 0;
  Error e = Error::None;
  if (number > 0 && face && face->read(number, v)) {
    if (asBool) e = Error::ReadParamConversionError;
  } else {
    e = number < 0 ? Error::ReadParamUnknown : readAxisParameter(ax, number, v, c.intervalNs);
    if (e == Error::None && asBool && axisParameter(number)->type != ParamType::Bool) e = Error::ReadParamConversionError;
  }
  fb.out.error = e != Error::None;
  fb.out.errorId = e;
  fb.out.busy = e == Error::None;
  b.state.valid = e == Error::None;
  if (e == Error::None) b.state.value = v;
  fb.sync();
}

void callWriteParameter(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int32_t number, double value, bool asBool,
                        const CallCtx& c, FaceParameters* face) {
  if (!edge(k, fb, ax, execute, c)) return;
  ConfigBehaviour& b = behaviourOf(fb);
  if (asBool) value = value != 0 ? 1.0 : 0.0;
  if (number < 0) {
    SdoAddress a;
    if (!decodeSdo(number, a)) return k.fail(fb, Error::WriteParamInvalid, c);
    b.pending = true;
    b.transfer = [a, value](Kernel& kk, FbSlot& f, Axis& x, uint64_t cycle) {
      const Error e = sdoWrite(x, a, value);
      kk.finish(f, nullptr, cycle, e == Error::None, false, e);
    };
    observe(ax, fb);
    fb.out.busy = true;
    fb.sync();
    return;
  }
  double old = 0;
  if (number > 0 && face && face->read(number, old)) {
    if (asBool || !std::isfinite(value)) return k.fail(fb, Error::WriteParamConversionError, c);
    if (value < 0) return k.fail(fb, Error::WriteParamInvalid, c);
    face->write(number, value);
    return done(k, fb, c);
  }
  const AxisParamInfo* p = axisParameter(number);
  Error e = Error::None;
  if (!p) e = Error::WriteParamInvalid;
  else if (asBool && p->type != ParamType::Bool) e = Error::WriteParamConversionError;
  else e = writeAxisParameter(ax, number, value);
  if (e != Error::None) return k.fail(fb, e, c);
  done(k, fb, c);
}

// ---------------------------------------------------------------- configuration FBs

void setPositionPeriod(Axis& ax, double period) {
  // The reported position carries over; on a modulo axis it is wrapped into the new period.
  const double reported = ax.reportPosition(ax.set().p);
  ax.mutableConfig().period = period > 0 ? period : 0;
  const double delta = ax.reportPosition(reported) - ax.set().p;
  if (delta != 0) ax.shiftPosition(delta);
}

void setIncrementsPerUnit(Axis& ax, double inc) {
  const double old = ax.config().drive.incrementsPerUnit;
  const double act = ax.actPosition();
  ax.mutableConfig().drive.incrementsPerUnit = inc;
  ax.drive().mutableConfig().incrementsPerUnit = inc;
  const double delta = act * old / inc - act;   // the same increments, now in the new unit
  if (delta != 0) ax.shiftPosition(delta);
}

void callChangeDynamicLimits(Kernel& k, FbSlot& fb, Axis& ax, bool execute, double vel, double acc, double dec,
                             double jerk, const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  auto positive = [](double x) { return std::isfinite(x) && x > 0; };
  if (!positive(vel) || !positive(acc) || !positive(dec) || !positive(jerk))
    return k.fail(fb, Error::SdlInvalidVelocityValues, c);
  if (!standstillOrPowerOff(ax)) return k.fail(fb, Error::SdlInvalidAxisState, c);
  AxisConfig& cfg = ax.mutableConfig();
  cfg.maxVelocity = vel;
  cfg.maxAcceleration = acc;
  cfg.maxDeceleration = dec;
  cfg.maxJerk = jerk;
  done(k, fb, c);
}

void callSetRampType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int rampType, const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  if (!standstillOrPowerOff(ax)) return k.fail(fb, Error::SrtNotStandstillOrPoweroff, c);
  if (rampType < 0 || rampType > 3) return k.fail(fb, Error::SrtInvalidRampType, c);
  ax.mutableConfig().ramp = static_cast<RampType>(rampType);
  done(k, fb, c);
}

void callSetCustomRampType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, bool ramp1Set, bool ramp2Set,
                           const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  (void)ramp1Set;
  (void)ramp2Set;
  if (!standstillOrPowerOff(ax)) return k.fail(fb, Error::SrtNotStandstillOrPoweroff, c);
  // The kernel plans every ramp itself and cannot call SMC_TG_IRAMPTYPE objects of the program.
  k.fail(fb, Error::SrtInvalidRampType, c);
}

void callSetMovementType(Kernel& k, FbSlot& fb, Axis& ax, bool execute, int movementType, double period,
                         const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  if ((movementType != 0 && movementType != 1) || (movementType == 0 && !(std::isfinite(period) && period > 0)))
    return k.fail(fb, Error::SmtInvalidMovementTypeOrPositionPeriod, c);
  if (ax.config().drive.kind != AxisKind::Virtual) return k.fail(fb, Error::SmtAxisNotVirtual, c);
  if (!standstillOrPowerOff(ax)) return k.fail(fb, Error::SmtNotStandstillOrPoweroff, c);
  setPositionPeriod(ax, movementType == 0 ? period : 0);
  done(k, fb, c);
}

void callSetSoftwareLimits(Kernel& k, FbSlot& fb, Axis& ax, bool execute, const SoftwareLimits& l, const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  if (!std::isfinite(l.positive) || !std::isfinite(l.negative) || !finiteNonNegative(l.deceleration) ||
      !finiteNonNegative(l.maxDistance) || (l.activated && l.negative > l.positive))
    return k.fail(fb, Error::WriteParamInvalid, c);
  AxisConfig& cfg = ax.mutableConfig();
  cfg.swLimitEnable = l.activated;
  cfg.swLimitPositive = l.positive;
  cfg.swLimitNegative = l.negative;
  cfg.swLimitDecelerate = l.decelerate;
  cfg.swLimitDeceleration = l.deceleration;
  cfg.swErrorMaxDistance = l.maxDistance;
  done(k, fb, c);
}

namespace {
bool powered(const Axis& ax) { return ax.powerRequested() || ax.operational(); }
}  // namespace

void callChangeGearingRatio(Kernel& k, FbSlot& fb, Axis& ax, bool execute, uint32_t denom, int32_t num,
                            double period, int movementType, const CallCtx& c) {
  if (!edge(k, fb, ax, execute, c)) return;
  if (denom == 0 || num <= 0 || (movementType != 0 && movementType != 1)) return k.fail(fb, Error::CgrZeroValues, c);
  const double inc = static_cast<double>(denom) / static_cast<double>(num);
  if (movementType == 0) {
    if (!(std::isfinite(period) && period > 0)) return k.fail(fb, Error::CgrInvalidPosPeriod, c);
    const double incs = period * inc;     // the period in increments must be whole
    if (std::fabs(incs - std::nearbyint(incs)) > 1e-9 * std::max(1.0, std::fabs(incs)))
      return k.fail(fb, Error::CgrPosPeriodNotIntegral, c);
  }
  if (powered(ax)) return k.fail(fb, Error::CgrDrivePowered, c);
  ConfigBehaviour& b = behaviourOf(fb);
  b.pending = true;
  b.transfer = [inc, period, movementType](Kernel& kk, FbSlot& f, Axis& x, uint64_t cycle) {
    if (powered(x)) return kk.finish(f, nullptr, cycle, false, false, Error::CgrDrivePowered);
    setIncrementsPerUnit(x, inc);
    setPositionPeriod(x, movementType == 0 ? period : 0);
    kk.finish(f, nullptr, cycle, true, false, Error::None);
  };
  observe(ax, fb);
  fb.out.busy = true;
  fb.sync();
}

}  // namespace stc::motion

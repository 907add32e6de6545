// The cam blocks of sm3_cam.st over core/Cam.h and core/Coupling.h
// (docs/motion-cam.md).  A cam is read from its MC_CAM_REF once, at the
// rising edge that needs it, into an immutable snapshot: later edits of the
// ST data take effect at the next MC_CamTableSelect, as in CODESYS.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <unistd.h>

#include "stdlib-motion/codesys_sm3/Sm3Face.h"
#include "stdlib-motion/core/Coupling.h"
#include "stdlib-motion/core/InputBounds.h"
#include "vm/FileSandbox.h"

using namespace stc::motion;
using namespace stc::motion::sm3face;

namespace {

constexpr uint16_t kCamStructId = 0xDC34;

// SMC_CAMXYVA (four LREALs; pce is untyped, so bindgen does not emit it).
struct CamXyvaRow {
  double dX, dY, dV, dA;
};
static_assert(sizeof(CamXyvaRow) == 32);

// The element size of a 1-D / 2-D table value (byVarType); 0 when unknown.
size_t varSize(uint8_t t) {
  switch (t) {
  case 1: case 2: return 2;
  case 3: case 4: case 5: return 4;
  case 6: return 8;
  default: return 0;
  }
}
double varValue(const uint8_t* p, uint8_t t) {
  switch (t) {
  case 1: { int16_t v; std::memcpy(&v, p, 2); return v; }
  case 2: { uint16_t v; std::memcpy(&v, p, 2); return v; }
  case 3: { int32_t v; std::memcpy(&v, p, 4); return v; }
  case 4: { uint32_t v; std::memcpy(&v, p, 4); return v; }
  case 5: { float v; std::memcpy(&v, p, 4); return v; }
  default: { double v; std::memcpy(&v, p, 8); return v; }
  }
}

bool sameX(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::max({1.0, std::fabs(a), std::fabs(b)}); }

// A snapshot of the cam an MC_CAM_REF describes, or the SMC error why not.
Error readCamRef(const sm3::MC_CAM_REF* ref, std::shared_ptr<const Cam>& out) {
  MotionSession& s = MotionSession::current();
  if (!ref || ref->wCAMStructID != kCamStructId) return Error::NoCamRefType;
  if (ref->__cam != 0) {
    auto it = s.cams.held.find(ref->__cam);
    if (it == s.cams.held.end()) return Error::NoCamRefType;
    out = it->second;
    return Error::None;
  }
  const int n = ref->nElements, nt = ref->nTappets;
  if (n < 2) return Error::CamTableEmptyMasterRange;
  if (n > kMaxCamElements || nt < 0 || nt > kMaxCamElements) return Error::NoCamRefType;
  // Tappets (pt) and points (pce) must lie in the controller's static memory.
  std::vector<Tappet> tappets;
  if (nt > 0) {
    if (!s.inImage(ref->pt, sizeof(sm3::SMC_CAMTappet) * static_cast<uint64_t>(nt))) return Error::NoCamRefType;
    const auto* t = static_cast<const sm3::SMC_CAMTappet*>(ref->pt);
    for (int i = 0; i < nt; ++i)
      tappets.push_back(Tappet{t[i].x, t[i].iGroupID, static_cast<TappetAction>(std::min<int>(static_cast<int>(t[i].ctaPos), 4)),
                               static_cast<TappetAction>(std::min<int>(static_cast<int>(t[i].ctaNeg), 4))});
  }
  Cam cam;
  std::string why;
  bool ok = false;
  const bool rangeGiven = ref->xEnd > ref->xStart;
  switch (ref->byType) {
  case 3: {   // XYVA
    if (!s.inImage(ref->pce, sizeof(CamXyvaRow) * static_cast<uint64_t>(n))) return Error::NoCamRefType;
    const auto* p = static_cast<const CamXyvaRow*>(ref->pce);
    std::vector<CamXYVA> pts;
    for (int i = 0; i < n; ++i) pts.push_back(CamXYVA{p[i].dX, p[i].dY, p[i].dV, p[i].dA});
    if (rangeGiven && (!sameX(pts.front().x, ref->xStart) || !sameX(pts.back().x, ref->xEnd))) return Error::CamTableDoesNotCoverMasterScale;
    ok = Cam::xyva(std::move(pts), std::move(tappets), cam, why);
    break;
  }
  case 1: case 2: {   // equidistant values / (x, y) pairs
    const size_t vs = varSize(ref->byVarType);
    const uint64_t cols = ref->byType == 1 ? 1 : 2;
    if (vs == 0 || !s.inImage(ref->pce, vs * cols * static_cast<uint64_t>(n))) return Error::NoCamRefType;
    const auto* p = static_cast<const uint8_t*>(ref->pce);
    if (ref->byType == 1) {
      if (!rangeGiven) return Error::CamTableInvalidMasterMinMax;
      std::vector<double> ys;
      for (int i = 0; i < n; ++i) ys.push_back(varValue(p + vs * static_cast<size_t>(i), ref->byVarType));
      ok = Cam::table1D(ref->xStart, ref->xEnd, std::move(ys), std::move(tappets), cam, why);
    } else {
      std::vector<std::array<double, 2>> pts;
      for (int i = 0; i < n; ++i)
        pts.push_back({varValue(p + vs * 2 * static_cast<size_t>(i), ref->byVarType), varValue(p + vs * (2 * static_cast<size_t>(i) + 1), ref->byVarType)});
      if (rangeGiven && (!sameX(pts.front()[0], ref->xStart) || !sameX(pts.back()[0], ref->xEnd))) return Error::CamTableDoesNotCoverMasterScale;
      ok = Cam::table2D(std::move(pts), std::move(tappets), cam, why);
    }
    break;
  }
  default:
    return Error::NoCamRefType;
  }
  if (!ok) return Error::CamTableInvalidMasterMinMax;
  out = std::make_shared<const Cam>(std::move(cam));
  return Error::None;
}

// Describes a cam the controller holds in an MC_CAM_REF (project.toml, SMC_ReadCAM).
void describeHeldCam(void* var, const Cam& cam, uint64_t id) {
  auto* r = static_cast<sm3::MC_CAM_REF*>(var);
  r->wCAMStructID = kCamStructId;
  r->byType = static_cast<uint8_t>(cam.kind());
  r->byVarType = 6;
  r->xStart = cam.xStart();
  r->xEnd = cam.xEnd();
  r->nElements = static_cast<int16_t>(std::min<size_t>(cam.points().size(), INT16_MAX));
  r->nTappets = static_cast<int16_t>(std::min<size_t>(cam.tappets().size(), INT16_MAX));
  r->pce = nullptr;
  r->pt = nullptr;
  r->__cam = id;
}

// The per-instance state of the blocks that are no axis commands.
struct SelectState : FbBehaviour {
  uint64_t id = 0;
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}
};

void MC_CamTableSelect(sm3::MC_CamTableSelect* self) {
  CallCtx c = callContext();
  Axis* slave = bind(self->Slave, c);
  Axis* master = slave ? bindMaster(self->Master, c) : nullptr;
  if (refuse(self, master ? slave : nullptr)) return;
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  if (!k.beginExecute(fb, self->Execute, c)) return fb.sync();
  fb.axis = slave;
  if (master == slave) return k.fail(fb, Error::NotReadyForMotion, c);
  std::shared_ptr<const Cam> cam;
  if (Error e = readCamRef(self->CamTable, cam); e != Error::None) return k.fail(fb, e, c);
  MotionSession& s = MotionSession::current();
  auto& st = behaviourOf<SelectState>(fb);
  s.cams.selections.erase(st.id);   // a re-select replaces this block's previous selection
  st.id = s.cams.nextId++;
  s.cams.selections[st.id] = CamSelection{cam, self->Periodic, self->MasterAbsolute, self->SlaveAbsolute};
  sm3::MC_CAM_ID& id = self->CamTableID;
  id.pCT = self->CamTable;
  id.Periodic = self->Periodic;
  id.MasterAbsolute = self->MasterAbsolute;
  id.SlaveAbsolute = self->SlaveAbsolute;
  id.StartMaster = cam->xStart();
  id.EndMaster = cam->xEnd();
  id.StartSlave = cam->at(cam->xStart()).y;
  id.EndSlave = cam->at(cam->xEnd()).y;
  id.__sel = st.id;
  k.finish(fb, &c, c.cycle, true, false, Error::None);
  fb.sync();
}

// The selection an MC_CAM_ID stands for, with the flags the ID carries now.
CamSelection selectionOf(const sm3::MC_CAM_ID& id) {
  MotionSession& s = MotionSession::current();
  auto it = s.cams.selections.find(id.__sel);
  if (it == s.cams.selections.end()) return {};
  CamSelection sel = it->second;
  sel.periodic = id.Periodic;
  sel.masterAbsolute = id.MasterAbsolute;
  sel.slaveAbsolute = id.SlaveAbsolute;
  return sel;
}

void publishTappets(void* instance, const TappetTracker::Groups& g, uint32_t resets) {
  auto* self = static_cast<sm3::MC_CamIn*>(instance);
  self->Tappets.nResets = resets;
  std::memcpy(self->Tappets.aGroups, g.data() + 1, sizeof self->Tappets.aGroups);
}

void MC_CamIn(sm3::MC_CamIn* self) {
  CallCtx c = callContext();
  Axis* slave = bind(self->Slave, c);
  if (refuse(self, slave) || rewired(self, *slave, c)) return;
  FbSlot& fb = slotOf(self, FbKind::CamIn);
  if (!(self->Execute && !fb.execute)) {   // without an edge the call only publishes (and may clear) the outputs
    kernel().beginExecute(fb, self->Execute, c);
    return fb.sync();
  }
  Axis* master = bindMaster(self->Master, c);   // read at the edge only
  if (refuse(self, master)) return;
  CamInInputs in;
  {   // the inputs are read at the edge only
    in.sel = selectionOf(self->CamTableID);
    in.masterOffset = self->MasterOffset;
    in.slaveOffset = self->SlaveOffset;
    in.masterScaling = self->MasterScaling;
    in.slaveScaling = self->SlaveScaling;
    in.startMode = enumOf<CamStartMode>(self->StartMode, 4);
    in.velocityDiff = self->VelocityDiff;
    in.acceleration = self->Acceleration;
    in.deceleration = self->Deceleration;
    in.jerk = self->Jerk;
    in.tappetHysteresis = self->TappetHysteresis;
    in.bufferMode = bufferModeOf(self->BufferMode);
    in.publishTappets = &publishTappets;
  }
  callCamIn(kernel(), fb, *master, *slave, self->Execute, in, c);
  mirrorCall(*slave);   // an edge may change the axis state
}

void MC_CamOut(sm3::MC_CamOut* self) {
  CallCtx c = callContext();
  Axis* slave = bind(self->Slave, c);
  if (refuse(self, slave) || rewired(self, *slave, c)) return;
  FbSlot& fb = slotOf(self, FbKind::Other);
  const bool edge = self->Execute && !fb.execute;
  callCouplingOut(kernel(), fb, *slave, self->Execute, true, c);
  if (edge) mirrorCall(*slave);
}

// SMC_CAMBounds(_Pos): the extremes of an XYVA cam coupled absolutely, for a master moving
// forwards at 0..dMasterVelMax with |acceleration| <= dMasterAccMax.
// The common start of the bExecute blocks that take an XYVA cam (640 for tables): at the
// rising edge, `body` gets the cam and finishes the block (Done in the same call).
template <class T, class Body>
void xyvaAtEdge(T* self, Body body) {
  CallCtx c = callContext();
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  if (!k.beginExecute(fb, self->bExecute, c)) return fb.sync();
  std::shared_ptr<const Cam> cam;
  if (Error e = readCamRef(self->CAM, cam); e != Error::None) return k.fail(fb, e, c);
  if (cam->kind() != CamKind::XYVA) return k.fail(fb, Error::CbNotImplemented, c);
  if (Error e = body(*cam); e != Error::None) return k.fail(fb, e, c);
  k.finish(fb, &c, c.cycle, true, false, Error::None);
  fb.sync();
}

template <class T>
void camBounds(T* self, bool withDynamics) {
  xyvaAtEdge(self, [&](const Cam& cam) {
    const double Vm = self->dMasterVelMax, Am = self->dMasterAccMax, Ms = self->dMasterScaling, Ss = self->dSlaveScaling;
    if (!(Vm >= 0 && Vm <= bounds::kVelocity) || !(Am >= 0 && Am <= bounds::kRate) || !validCamScaling(Ms) || !validCamScaling(Ss))
      return Error::CbNotImplemented;   // NaN fails every comparison
    const CamExtremes& e = cam.extremes();
    auto range = [&](double lo, double hi, double f, double& mn, double& mx) {
      mn = std::min(lo * f, hi * f);
      mx = std::max(lo * f, hi * f);
    };
    range(e.yMin, e.yMax, Ss, self->dMinPos, self->dMaxPos);
    if constexpr (requires { self->dMaxVel; }) {
      if (withDynamics) {
        range(std::min(e.dyMin, 0.0), std::max(e.dyMax, 0.0), Ss * Ms * Vm, self->dMinVel, self->dMaxVel);
        // a = Ss·(y''·(Ms·vm)² + y'·Ms·am): sampled along the cam (64 points per segment).
        double aMin = 0, aMax = 0;
        const size_t n = cam.segments() * 64;
        for (size_t i = 0; i <= n; ++i) {
          const CamSample s = cam.at(cam.xStart() + cam.length() * static_cast<double>(i) / static_cast<double>(n));
          const double curv = Ss * s.ddy * Ms * Ms * Vm * Vm, lin = std::fabs(Ss * s.dy * Ms * Am);
          aMax = std::max(aMax, std::max(curv, 0.0) + lin);
          aMin = std::min(aMin, std::min(curv, 0.0) - lin);
        }
        self->dMaxAccDec = aMax;
        self->dMinAccDec = aMin;
      }
    }
    return Error::None;
  });
}
void SMC_CAMBounds(sm3::SMC_CAMBounds* self) { camBounds(self, true); }
void SMC_CAMBounds_Pos(sm3::SMC_CAMBounds_Pos* self) { camBounds(self, false); }

// SMC_CamEditor: bCAMchanged for one call when the cam's header or data changed.
struct EditorState : FbBehaviour {
  uint64_t hash = 0;
  bool seen = false;
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}
};
uint64_t fnv(const void* p, size_t n, uint64_t h) {
  const auto* b = static_cast<const uint8_t*>(p);
  for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}
void SMC_CamEditor(sm3::SMC_CamEditor* self) {
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  auto& st = behaviourOf<EditorState>(fb);
  self->bCAMchanged = false;
  if (!self->bEnable) {
    st.seen = false;
    self->bError = false;
    self->nErrorID = 0;
    return;
  }
  std::shared_ptr<const Cam> cam;
  if (Error e = readCamRef(self->cam, cam); e != Error::None) {
    self->bError = true;
    self->nErrorID = static_cast<decltype(self->nErrorID)>(smcError(e));
    return;
  }
  self->bError = false;
  self->nErrorID = 0;
  uint64_t h = fnv(self->cam, offsetof(sm3::MC_CAM_REF, __cam) + sizeof(uint64_t), 1469598103934665603ull);
  for (const CamXYVA& p : cam->points()) h = fnv(&p, sizeof p, h);
  for (const Tappet& t : cam->tappets()) h = fnv(&t, sizeof t, h);
  self->bCAMchanged = st.seen && h != st.hash;
  st.hash = h;
  st.seen = true;
  (void)k;
}

// SMC_CamRegister: the tappets of a cam along the master position only (periodic).
struct RegisterState : FbBehaviour {
  std::shared_ptr<const Cam> cam;
  TappetTracker tracker;
  double kLast = 0;
  const void* camVar = nullptr;
  std::array<bool, kMaxTappetGroups + 1> initial{};
  void start(Kernel&, FbSlot&, Axis&, int64_t) override {}
};
void releaseRegister(RegisterState& st) {
  if (!st.camVar) return;
  auto& users = MotionSession::current().cams.registerUsers;
  if (--users[st.camVar] <= 0) users.erase(st.camVar);
  st.camVar = nullptr;
}
void SMC_CamRegister(sm3::SMC_CamRegister* self) {
  CallCtx c = callContext();
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  auto& st = behaviourOf<RegisterState>(fb);
  const bool rising = self->Enable && !fb.execute;
  fb.execute = self->Enable;
  fb.out.endOfProfile = false;
  if (!self->Enable) {
    releaseRegister(st);
    fb.out = FbOutputs{};
    return fb.sync();
  }
  if (fb.out.error) return fb.sync();   // held until Enable falls
  Axis* master = bindMaster(self->Master, c);
  if (!master) return k.fail(fb, Error::NotReadyForMotion, c);
  const double Ms = self->MasterScaling, Mo = self->MasterOffset, h = self->TappetHysteresis, dtc = self->DeadTimeCompensation;
  const Kinematic m = masterState(*master);
  if (rising) {
    std::shared_ptr<const Cam> cam;
    if (self->CamTable && self->CamTable->wCAMStructID == kCamStructId && self->CamTable->__cam == 0 && self->CamTable->pt &&
        MotionSession::current().inImage(self->CamTable->pt, sizeof(sm3::SMC_CAMTappet) * static_cast<uint64_t>(std::max<int>(self->CamTable->nTappets, 0)))) {
      const auto* t = static_cast<const sm3::SMC_CAMTappet*>(self->CamTable->pt);
      for (int i = 0; i < self->CamTable->nTappets; ++i)
        if (t[i].iGroupID < 1 || t[i].iGroupID > kMaxTappetGroups) return k.fail(fb, Error::CrTooManyTappets, c);
    }
    if (Error e = readCamRef(self->CamTable, cam); e != Error::None) return k.fail(fb, e, c);
    if (cam->tappets().empty()) return k.fail(fb, Error::CrNoTappetsInCam, c);
    if (!validCamScaling(Ms) || !bounds::position(Mo) || !std::isfinite(h) || h < 0 || h > cam->length() || !std::isfinite(dtc) ||
        std::fabs(dtc) > 10)
      return k.fail(fb, Error::CiScalingIncorrect, c);
    auto& users = MotionSession::current().cams.registerUsers;
    if (users[self->CamTable] >= 32) return k.fail(fb, Error::CrMoreThan32Accesses, c);
    ++users[self->CamTable];
    st.camVar = self->CamTable;
    st.cam = cam;
    for (int g = 1; g <= kMaxTappetGroups; ++g) st.initial[static_cast<size_t>(g)] = static_cast<const bool*>(self->bTappet)[g - 1];
  }
  const Cam& cam = *st.cam;
  // DeadTimeCompensation fires earlier (> 0) or later (< 0) by velocity × time.
  const double X = Ms * (m.p + m.v * dtc) + Mo;
  const double kAbs = std::floor((X - cam.xStart()) / cam.length()), xw = X - kAbs * cam.length();
  bool fired = false;
  if (rising) {
    st.tracker.reset(cam.tappets(), xw, h);
  } else {
    if (kAbs != st.kLast) {
      const bool fwd = kAbs > st.kLast;
      fb.out.endOfProfile = fwd;
      fired |= st.tracker.move(fwd ? cam.xEnd() : cam.xStart());
      st.tracker.wrap(fwd ? cam.xStart() : cam.xEnd());
    }
    fired |= st.tracker.move(xw);
  }
  st.kLast = kAbs;
  if (fired) {
    const auto& g = st.tracker.groups();
    for (int i = 1; i <= kMaxTappetGroups; ++i)
      if (g[static_cast<size_t>(i)] & 8) static_cast<bool*>(self->bTappet)[i - 1] = TappetTracker::value(g[static_cast<size_t>(i)], st.initial[static_cast<size_t>(i)]);
  }
  fb.out.busy = true;
  fb.sync();
}

void SMC_GetCamSlaveSetPosition(sm3::SMC_GetCamSlaveSetPosition* self) {
  CallCtx c = callContext();
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  if (!self->Enable) {
    fb.out = FbOutputs{};
    return fb.sync();
  }
  Axis* master = bindMaster(self->Master, c);
  if (!master) return k.fail(fb, Error::NotReadyForMotion, c);
  const CamSelection sel = selectionOf(self->CamTableID);
  if (!sel.cam) return k.fail(fb, Error::CiNoCamSelected, c);
  if (!validCamScaling(self->MasterScaling) || !validCamScaling(self->SlaveScaling) || !bounds::position(self->MasterOffset) ||
      !bounds::position(self->SlaveOffset))
    return k.fail(fb, Error::CiScalingIncorrect, c);
  Kinematic m = masterState(*master), out;
  if (master->isModulo()) m.p -= master->config().period * std::floor(m.p / master->config().period);
  if (!camSlaveState(sel, self->MasterOffset, self->SlaveOffset, self->MasterScaling, self->SlaveScaling, m, out))
    return k.fail(fb, Error::CiMasterOutOfScale, c);
  self->fStartPosition = out.p;
  self->fStartVelocity = out.v;
  self->fStartAcceleration = out.a;
  fb.out = FbOutputs{};
  fb.out.busy = true;
  fb.sync();
}

// Opens the file a program names, inside the data directory (vm/FileSandbox.h); -1 when
// the name is refused or the file cannot be opened.
int camFile(const char* name, stc::vm::FileAccess access) {
  std::string why;
  return stc::vm::openInside(MotionSession::current().filesDir(), std::string(name, strnlen(name, 255)), access, why);
}

void SMC_ReadCAM(sm3::SMC_ReadCAM* self) {
  CallCtx c = callContext();
  Kernel& k = kernel();
  FbSlot& fb = slotOf(self, FbKind::Other);
  if (!k.beginExecute(fb, self->bExecute, c)) return fb.sync();
  const int fd = camFile(self->sFileName, stc::vm::FileAccess::Read);
  if (fd < 0) return k.fail(fb, Error::RcamFileDoesntExist, c);
  std::string text;
  switch (stc::vm::readAndClose(fd, kMaxProjectFileBytes, text)) {
  case stc::vm::ReadResult::Ok: break;
  case stc::vm::ReadResult::Failed: return k.fail(fb, Error::RcamFileDoesntExist, c);
  case stc::vm::ReadResult::TooBig: return k.fail(fb, Error::RcamTooMuchData, c);
  }
  Cam cam;
  std::string name, detail;
  switch (readCamText(text, cam, name, detail)) {
  case CamFileError::None: break;
  case CamFileError::TooMuchData: return k.fail(fb, Error::RcamTooMuchData, c);
  case CamFileError::WrongType: return k.fail(fb, Error::RcamWrongCompileType, c);
  case CamFileError::WrongVersion: return k.fail(fb, Error::RcamWrongVersion, c);
  case CamFileError::UnexpectedEnd: return k.fail(fb, Error::RcamUnexpectedEof, c);
  }
  MotionSession& s = MotionSession::current();
  // The held cam of this block's previous read is replaced (couplings keep their snapshot).
  s.cams.held.erase(self->CAM.__cam);
  const uint64_t id = s.cams.nextId++;
  auto held = std::make_shared<const Cam>(std::move(cam));
  s.cams.held[id] = held;
  describeHeldCam(&self->CAM, *held, id);
  std::snprintf(self->CAM.strCAMName, sizeof self->CAM.strCAMName, "%s", name.c_str());
  k.finish(fb, &c, c.cycle, true, false, Error::None);
  fb.sync();
}

void SMC_WriteCAM(sm3::SMC_WriteCAM* self) {
  xyvaAtEdge(self, [&](const Cam& cam) {
    const int fd = camFile(self->sFileName, stc::vm::FileAccess::Write);
    if (fd < 0) return Error::RcamFileDoesntExist;
    const std::string text =
        writeCamText(cam, std::string(self->CAM->strCAMName, strnlen(self->CAM->strCAMName, sizeof self->CAM->strCAMName)));
    std::FILE* out = ::fdopen(fd, "wb");
    if (!out) {
      ::close(fd);
      return Error::RcamFileDoesntExist;
    }
    const bool ok = std::fwrite(text.data(), 1, text.size(), out) == text.size();
    return std::fclose(out) == 0 && ok ? Error::None : Error::RcamFileDoesntExist;
  });
}

}  // namespace

namespace stc::motion {

void registerSm3CamNatives(MotionLibrary& lib) {
  STC_SM3_NATIVE(MC_CamTableSelect, MC_CamTableSelect)
  STC_SM3_NATIVE(MC_CamIn, MC_CamIn)
  STC_SM3_NATIVE(MC_CamOut, MC_CamOut)
  STC_SM3_NATIVE(SMC_CAMBounds, SMC_CAMBounds)
  STC_SM3_NATIVE(SMC_CAMBounds_Pos, SMC_CAMBounds_Pos)
  STC_SM3_NATIVE(SMC_CamEditor, SMC_CamEditor)
  STC_SM3_NATIVE(SMC_CamRegister, SMC_CamRegister)
  STC_SM3_NATIVE(SMC_GetCamSlaveSetPosition, SMC_GetCamSlaveSetPosition)
  STC_SM3_NATIVE(SMC_ReadCAM, SMC_ReadCAM)
  STC_SM3_NATIVE(SMC_WriteCAM, SMC_WriteCAM)
  lib.addCamFace({"MC_CAM_REF", &describeHeldCam});
}

}  // namespace stc::motion

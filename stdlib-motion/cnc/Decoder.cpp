#include "stdlib-motion/cnc/Decoder.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxCoord = 1e9;      // coordinates, centres, radii, distances, D
constexpr double kMaxPosition = 1e10;  // a position after offsets and increments
constexpr double kMaxFeed = 1e9;       // F, FF
constexpr double kMaxAccel = 1e12;     // E, E-, EF, EF-
constexpr double kMaxDwell = 1e6;      // s
constexpr double kMaxSweep = 36000;    // deg (100 turns)

constexpr uint32_t B(char c) { return bit(c); }
constexpr uint32_t kAxesMask =
    B('X') | B('Y') | B('Z') | B('A') | B('B') | B('C') | B('P') | B('Q') | B('U') | B('V') | B('W');
constexpr uint32_t kIJK = B('I') | B('J') | B('K');
constexpr uint32_t kModalMask = B('F') | B('E') | (1u << SlotEMinus) | (1u << SlotFF) | (1u << SlotEF) |
                                (1u << SlotEFMinus) | B('S');
constexpr char kAxisLetters[kAxisCount] = {'X', 'Y', 'Z', 'A', 'B', 'C', 'P', 'Q', 'U', 'V', 'W'};

enum class Group : uint8_t { Motion, Other, Offset, Plane, Dist, Centre, Tool, Smooth, Loop };

Group groupOf(int g) {
  switch (g) {
    case 0: case 1: case 2: case 3: case 5: case 6: case 8: case 9: case 10: return Group::Motion;
    case 53: case 54: case 55: case 56: return Group::Offset;
    case 16: case 17: case 18: case 19: return Group::Plane;
    case 90: case 91: return Group::Dist;
    case 98: case 99: return Group::Centre;
    case 40: case 41: case 42: return Group::Tool;
    case 50: case 51: case 52: return Group::Smooth;
    case 60: case 61: return Group::Loop;
    default: return Group::Other;   // 4, 20, 25, 36, 37, 75, 92
  }
}

// The words a travel command reads (besides the modal F/E/S words).
uint32_t motionMask(int g) {
  switch (g) {
    case 2: case 3: return kAxesMask | kIJK | B('R') | B('T');
    case 6: return kAxesMask | B('I') | B('J');
    case 8: case 9: return kAxesMask | kIJK | B('R');
    default: return kAxesMask;
  }
}
uint32_t otherMask(int g) {
  switch (g) {
    case 4: return B('T');
    case 20: case 25: return B('L') | B('K');
    case 36: case 37: return B('O') | B('D');
    case 92: return kAxesMask;
    default: return 0;
  }
}

std::string gName(int g) { return "G" + std::to_string(g); }

int lowestBit(uint32_t m) { return __builtin_ctz(m); }

// Wraps an angle difference into the sweep of a counter-clockwise (0, 2pi] or
// clockwise [-2pi, 0) arc.
double sweepOf(double d, bool ccw) {
  const double two = 2 * kPi;
  if (ccw) {
    d = std::fmod(d, two);
    if (d <= 0) d += two;
  } else {
    d = std::fmod(d, two);
    if (d >= 0) d -= two;
  }
  return d;
}

}  // namespace

// ---------------------------------------------------------------- queue

ElementQueue::ElementQueue(size_t capacity) : slots_(std::max(capacity, kMinCapacity)) {}

Element& ElementQueue::push() {
  size_t w = (read_ + size_) % slots_.size();
  ++size_;
  slots_[w] = Element();
  return slots_[w];
}

void ElementQueue::pop() {
  if (!size_) return;
  read_ = (read_ + 1) % slots_.size();
  --size_;
}

void ElementQueue::clear() {
  read_ = size_ = 0;
  endOfList = false;
}

const char* toString(StepStatus s) {
  switch (s) {
    case StepStatus::Progress: return "progress";
    case StepStatus::QueueFull: return "queue full";
    case StepStatus::Sync: return "sync";
    case StepStatus::Finished: return "finished";
  }
  return "?";
}

// ---------------------------------------------------------------- decoder

Decoder::Decoder(const SourceManager& sm, uint32_t file, DiagnosticsEngine& diags, const DecoderOptions& opts,
                 VariableAccess* vars)
    : text_(sm.file(file).text), opts_(opts), vars_(vars), rep_(&diags, file),
      parser_(text_, rep_), quietRep_(nullptr, file), quietParser_(text_, quietRep_) {
  quietRep_.quiet = true;
  reset();
}

void Decoder::reset() {
  offset_ = 0;
  line_ = 1;
  lastLine_ = 0;
  sawBlock_ = finished_ = false;
  name_ = {};
  pos_ = opts_.startPosition;
  offsetVec_ = Pos{};
  motion_ = -1;
  incremental_ = centreAbsolute_ = false;
  setPlane(17);
  F_ = opts_.defaultVel;
  E_ = opts_.defaultAcc;
  Ed_ = opts_.defaultDec;
  FF_ = opts_.defaultRapidVel;
  EF_ = opts_.defaultRapidAcc;
  EFd_ = opts_.defaultRapidDec;
  S_ = 0;
  toolSide_ = ToolSide::Off;
  toolRadius_ = 0;
  smoothing_ = Smoothing::Off;
  smoothDist_ = 0;
  loopAvoid_ = false;
  marks_ = 0;
  axesUsed_ = (1u << AxX) | (1u << AxY) | (1u << AxZ);
  std::fill(std::begin(axisFirstUse_), std::end(axisFirstUse_), 0u);
  toolOnAt_ = 0;
  counter_ = -1;
  feedWarned_ = false;
  objNo_ = 0;
  havePending_ = false;
  lastTangentValid_ = false;
  syncQueued_ = jumped_ = false;
  jumps_ = 0;
  // The index stays: the text has not changed.
}

void Decoder::setPlane(int code) {
  switch (code) {
    case 18:   // ZX: u = Z, v = X, normal Y
      plane_ = Plane::ZX;
      u_ = {0, 0, 1};
      v_ = {1, 0, 0};
      n_ = {0, 1, 0};
      break;
    case 19:   // YZ: u = Y, v = Z, normal X
      plane_ = Plane::YZ;
      u_ = {0, 1, 0};
      v_ = {0, 0, 1};
      n_ = {1, 0, 0};
      break;
    default:
      plane_ = Plane::XY;
      u_ = {1, 0, 0};
      v_ = {0, 1, 0};
      n_ = {0, 0, 1};
      break;
  }
}

void Decoder::indexBlock(const Block& b) {
  if (b.hasN) {
    if (const BlockIndex::Entry* first = index_.insert(b.n, b.begin, b.line))
      rep_.error(b.nBegin, b.nEnd, "duplicate block number N" + std::to_string(b.n), "gcode-duplicate-n")
          .note(rep_.loc(first->offset), "N" + std::to_string(b.n) + " is first used on line " +
                                             std::to_string(first->line));
  }
  if (b.hasLabel) {
    if (const BlockIndex::Entry* first = labels_.insert(b.label, b.begin, b.line))
      rep_.error(b.labelBegin, b.labelEnd, "duplicate jump label L!" + std::to_string(b.label), "gcode-duplicate-n")
          .note(rep_.loc(first->offset), "L!" + std::to_string(b.label) + " is first defined on line " +
                                             std::to_string(first->line));
  }
}

uint32_t Decoder::cmdBegin(const Block& b, const Cmd& c) const {
  if (c.word >= 0) return b.words[c.word].begin;
  if (b.count) return b.words[0].begin;
  return b.begin;
}

uint32_t Decoder::cmdStop(const Block& b, const Cmd& c) const {
  if (c.word >= 0) return b.words[c.word].end;
  if (b.count) return b.words[0].end;
  return b.begin;
}

StepResult Decoder::step(ElementQueue& out, uint32_t maxBlocks) {
  StepResult r;
  int32_t obj0 = objNo_;
  for (;;) {
    if (finished_) {
      r.status = StepStatus::Finished;
      break;
    }
    if (opts_.stopAtFirstError && rep_.errors()) {
      finished_ = true;
      out.endOfList = true;
      r.status = StepStatus::Finished;
      break;
    }
    if (out.free() < 3) {
      r.status = StepStatus::QueueFull;
      break;
    }
    if (r.blocks >= maxBlocks) {
      r.status = StepStatus::Progress;
      break;
    }
    if (offset_ >= text_.size()) {
      finish(out);
      r.status = StepStatus::Finished;
      break;
    }
    uint32_t begin = offset_;
    uint32_t next = parser_.parse(offset_, line_, block_);
    if (begin >= indexedTo_) {
      indexBlock(block_);
      indexedTo_ = next;
      indexedLine_ = line_ + 1;
    }
    offset_ = next;
    ++line_;
    ++r.blocks;
    const Block& b = block_;
    if (b.header) {
      if (sawBlock_ && b.nameBegin == b.nameEnd && !b.bad) {
        // A lone '%' after the blocks closes the program (RS274 files).
        size_t rest = text_.find_first_not_of(" \t\r\n\f\v", offset_);
        if (rest != std::string_view::npos)
          rep_.warning(static_cast<uint32_t>(rest), static_cast<uint32_t>(rest + 1),
                       "text after the closing '%' is ignored", "gcode-after-end");
        finish(out);
        r.status = StepStatus::Finished;
        break;
      }
      if (sawBlock_)
        rep_.error(b.headerAt, b.nameEnd,
                   "the program header '%name' must be the first line", "gcode-syntax");
      else
        name_ = text_.substr(b.nameBegin, b.nameEnd - b.nameBegin);
      sawBlock_ = true;
      continue;
    }
    if (b.empty() && !b.hasN && !b.hasLabel) continue;
    sawBlock_ = true;
    if (b.bad) continue;
    if (b.skip && opts_.skipSlashBlocks) continue;
    if (opts_.requireBlockNumbers && !b.hasN && b.count) {
      rep_.error(b.words[0].begin, b.words[0].end, "every block needs a block number N in this dialect",
                 "gcode-missing-word");
      continue;
    }
    lastLine_ = b.line;
    if (b.count) decodeBlock(b, out);
    if (jumped_) {
      jumped_ = false;
      offset_ = jumpOffset_;
      line_ = jumpLine_;
    }
    if (syncQueued_) {
      syncQueued_ = false;
      r.status = StepStatus::Sync;
      break;
    }
  }
  r.elements = static_cast<uint32_t>(objNo_ - obj0);
  return r;
}

void Decoder::finish(ElementQueue& out) {
  if (havePending_) flushPending(out, nullptr);
  out.endOfList = true;
  finished_ = true;
}

// ---------------------------------------------------------------- words

bool Decoder::resolve(const Block& b, const Word& w, double& v) {
  switch (w.kind) {
    case WordKind::Literal:
      v = w.value;
      return true;
    case WordKind::LabelRef:
      rep_.error(w.begin, w.end, "'" + std::string(text_.substr(w.begin, w.end - w.begin)) +
                                     "' is a jump label, not a number",
                 "gcode-syntax");
      return false;
    case WordKind::Variable:
      break;
  }
  std::string_view name = text_.substr(w.nameBegin, w.nameEnd - w.nameBegin);
  if (!vars_) {
    rep_.error(w.begin, w.end, "'$" + std::string(name) + "$' needs a variable source (none was given to the decoder)",
               "gcode-variable");
    return false;
  }
  if (!vars_->read(name, v)) {
    rep_.error(w.begin, w.end, "unknown variable '$" + std::string(name) + "$'", "gcode-variable");
    return false;
  }
  if (w.negate) v = -v;
  std::string msg = checkWordValue(w.slot, v);
  if (!msg.empty()) {
    rep_.error(w.begin, w.end, msg + " ($" + std::string(name) + "$ = " + formatNumber(v) + ")", "gcode-range");
    return false;
  }
  return true;
}

bool Decoder::modalWords(const Block& b) {
  if (!(b.present & kModalMask)) return true;
  bool ok = true;
  struct Def {
    uint8_t slot;
    double* target;
    double max;
    const char* what;
    const char* maxText;
    SmcError id;
  };
  const Def defs[] = {
      {slotOf('F'), &F_, kMaxFeed, "the path velocity F", "1e9", SmcError::InvalidSyntax},
      {slotOf('E'), &E_, kMaxAccel, "the path acceleration E", "1e12", SmcError::AccTooLittle},
      {SlotEMinus, &Ed_, kMaxAccel, "the path deceleration E-", "1e12", SmcError::RetTooLittle},
      {SlotFF, &FF_, kMaxFeed, "the G0 velocity FF", "1e9", SmcError::InvalidSyntax},
      {SlotEF, &EF_, kMaxAccel, "the G0 acceleration EF", "1e12", SmcError::AccTooLittle},
      {SlotEFMinus, &EFd_, kMaxAccel, "the G0 deceleration EF-", "1e12", SmcError::RetTooLittle},
  };
  for (const Def& d : defs) {
    const Word* w = b.find(d.slot);
    if (!w) continue;
    double v;
    if (!resolve(b, *w, v)) {
      ok = false;
      continue;
    }
    if (!(v > 0) || v > d.max) {
      rep_.error(w->begin, w->end,
                 std::string(d.what) + " must be > 0 and at most " + d.maxText + " (is " + formatNumber(v) + ")",
                 "gcode-range", d.id);
      ok = false;
      continue;
    }
    *d.target = v;
  }
  if (const Word* w = b.find(slotOf('S'))) {
    double v;
    if (!resolve(b, *w, v)) return false;
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(w->begin, w->end, "S is out of range (magnitude above 1e9)", "gcode-range");
      return false;
    }
    S_ = v;
  }
  return ok;
}

bool Decoder::checkExclusiveAxes(const Block& b) {
  static constexpr struct { Axis a, u; SmcError id; } kPairs[] = {
      {AxA, AxU, SmcError::ExclusiveAU}, {AxB, AxV, SmcError::ExclusiveBV}, {AxC, AxW, SmcError::ExclusiveCW}};
  bool ok = true;
  for (const auto& p : kPairs) {
    for (Axis ax : {p.a, p.u}) {
      uint8_t s = slotOf(kAxisLetters[ax]);
      if (b.at[s] < 0) continue;
      const Word& w = b.words[b.at[s]];
      Axis other = ax == p.a ? p.u : p.a;
      if (axisFirstUse_[other]) {
        char l1 = kAxisLetters[p.a], l2 = kAxisLetters[p.u];
        rep_.error(w.begin, w.end,
                   std::string("axes ") + l1 + " and " + l2 + " cannot be used in one program (they share an interpolator channel)",
                   "gcode-exclusive-axes", p.id)
            .note(rep_.loc(axisFirstUse_[other] - 1), std::string("'") + kAxisLetters[other] + "' is used here");
        ok = false;
      } else if (!axisFirstUse_[ax]) {
        axisFirstUse_[ax] = w.begin + 1;
      }
    }
  }
  return ok;
}

bool Decoder::target(const Block& b, bool incremental, Pos& tgt) {
  tgt = pos_;
  uint32_t axes = b.present & kAxesMask;
  if (!axes) return true;
  if ((axes & (B('A') | B('B') | B('C') | B('U') | B('V') | B('W'))) && !checkExclusiveAxes(b)) return false;
  bool ok = true;
  for (int a = 0; a < kAxisCount; ++a) {
    int8_t i = b.at[slotOf(kAxisLetters[a])];
    if (i < 0) continue;
    const Word& w = b.words[i];
    double v;
    if (!resolve(b, w, v)) {
      ok = false;
      continue;
    }
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(w.begin, w.end, std::string("coordinate ") + kAxisLetters[a] + " is out of range (magnitude above 1e9)",
                 "gcode-range");
      ok = false;
      continue;
    }
    double p = incremental ? pos_[a] + v : v + offsetVec_[a];
    if (std::fabs(p) > kMaxPosition) {
      rep_.error(w.begin, w.end, std::string("the position of ") + kAxisLetters[a] + " (" + formatApprox(p) +
                                     ") is out of range after offsets and increments",
                 "gcode-range");
      ok = false;
      continue;
    }
    tgt[a] = p;
    axesUsed_ |= static_cast<uint16_t>(1u << a);
  }
  return ok;
}

// ---------------------------------------------------------------- blocks

bool Decoder::collectCommands(const Block& b, BlockCmds& c) {
  for (int i = 0; i < b.gCount; ++i) {
    const Word& w = b.words[b.g[i]];
    int code = static_cast<int>(w.value);
    Cmd* slot = nullptr;
    switch (groupOf(code)) {
      case Group::Motion: slot = &c.motion; break;
      case Group::Other: slot = &c.other; break;
      case Group::Offset: slot = &c.offset; break;
      case Group::Plane: slot = &c.plane; break;
      case Group::Dist: slot = &c.dist; break;
      case Group::Centre: slot = &c.centre; break;
      case Group::Tool: slot = &c.tool; break;
      case Group::Smooth: slot = &c.smooth; break;
      case Group::Loop: slot = &c.loop; break;
    }
    if (slot->code >= 0) {
      const Word& f = b.words[slot->word];
      rep_.error(w.begin, w.end, gName(code) + " conflicts with " + gName(slot->code) + " in the same block",
                 "gcode-conflict")
          .note(rep_.loc(f.begin), gName(slot->code) + " is here", rep_.range(f.begin, f.end));
      return false;
    }
    *slot = Cmd{code, b.g[i]};
  }
  // One command per block: a travel command, a non-modal command or an offset
  // that reads axis words (G53 reads none and goes with anything).
  const Cmd* cmds[] = {&c.motion, &c.other, &c.offset};
  const Cmd* first = nullptr;
  for (const Cmd* x : cmds) {
    if (x->code < 0 || x->code == 53) continue;
    if (first) {
      const Cmd* second = x->word > first->word ? x : first;
      const Cmd* earlier = second == x ? first : x;
      const Word& w = b.words[second->word];
      const Word& f = b.words[earlier->word];
      rep_.error(w.begin, w.end, gName(second->code) + " and " + gName(earlier->code) +
                                     " cannot be in the same block; write them in separate blocks",
                 "gcode-conflict")
          .note(rep_.loc(f.begin), gName(earlier->code) + " is here", rep_.range(f.begin, f.end));
      return false;
    }
    first = x;
  }
  return true;
}

bool Decoder::checkClaims(const Block& b, const BlockCmds& c) {
  struct Consumer {
    int code;
    uint32_t mask;
    bool isM;
  };
  Consumer list[8];
  int n = 0;
  if (c.motion.code >= 0) list[n++] = {c.motion.code, motionMask(c.motion.code), false};
  if (c.other.code >= 0) list[n++] = {c.other.code, otherMask(c.other.code), false};
  if (c.offset.code >= 0 && c.offset.code != 53) list[n++] = {c.offset.code, kAxesMask, false};
  if (c.plane.code == 16) list[n++] = {16, kIJK, false};
  if (c.tool.code == 41 || c.tool.code == 42) list[n++] = {c.tool.code, B('D'), false};
  if (c.smooth.code == 51 || c.smooth.code == 52) list[n++] = {c.smooth.code, B('D'), false};
  if (b.has('M')) list[n++] = {-1, B('K') | B('L'), true};
  auto name = [&](const Consumer& x) {
    return x.isM ? std::string("the M function") : gName(x.code);
  };
  uint32_t claimed = kModalMask | B('G') | B('M') | B('H');
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      uint32_t both = list[i].mask & list[j].mask & b.present;
      if (!both) continue;
      const Word& w = b.words[b.at[lowestBit(both)]];
      rep_.error(w.begin, w.end, "'" + slotName(w.slot) + "' is read by both " + name(list[i]) + " and " +
                                     name(list[j]) + "; write them in separate blocks",
                 "gcode-conflict");
      return false;
    }
    claimed |= list[i].mask;
  }
  uint32_t unused = b.present & ~claimed;
  while (unused) {
    int s = lowestBit(unused);
    unused &= unused - 1;
    const Word& w = b.words[b.at[s]];
    std::string where = c.motion.code >= 0 ? " in a " + gName(c.motion.code) + " block"
                        : c.other.code >= 0 ? " in a " + gName(c.other.code) + " block"
                                            : std::string(" in this block");
    rep_.warning(w.begin, w.end, "'" + slotName(static_cast<uint8_t>(s)) + "' has no effect" + where,
                 "gcode-unused-word");
  }
  return true;
}

void Decoder::startElement(const Block& b, const Cmd& cmd, MoveType type, Element& e) const {
  e.line = static_cast<int32_t>(b.line);
  e.column = static_cast<int32_t>(cmdBegin(b, cmd) - b.begin + 1);
  e.blockNo = b.hasN ? b.n : -1;
  e.type = type;
  e.plane = plane_;
  e.axesUsed = axesUsed_;
  e.start = e.end = pos_;
  if (type == MoveType::LinPos) {
    e.vel = FF_ > 0 ? FF_ : F_;
    e.acc = EF_ > 0 ? EF_ : E_;
    e.dec = EFd_ > 0 ? EFd_ : Ed_;
  } else {
    e.vel = F_;
    e.acc = E_;
    e.dec = Ed_;
  }
  e.s = S_;
  e.toolSide = toolSide_;
  e.toolRadius = toolRadius_;
  e.smoothing = smoothing_;
  e.smoothDist = smoothDist_;
  e.loopAvoid = loopAvoid_;
}

bool Decoder::switchPoints(const Block& b, Element& e) {
  bool ok = true;
  for (int i = 0; i < b.switchCount; ++i) {
    const Block::Switch& sp = b.switches[i];
    const Word& hw = b.words[sp.h];
    double h;
    if (!resolve(b, hw, h)) {
      ok = false;
      continue;
    }
    double p = 0;
    bool rel = false;
    if (sp.pos >= 0) {
      const Word& pw = b.words[sp.pos];
      if (!resolve(b, pw, p)) {
        ok = false;
        continue;
      }
      rel = pw.slot == slotOf('O');
      if (rel && !(p >= 0 && p <= 1)) {
        rep_.error(pw.begin, pw.end, "the relative switch position O must be in [0, 1] (is " + formatNumber(p) + ")",
                   "gcode-range");
        ok = false;
        continue;
      }
      if (!rel && std::fabs(p) > kMaxCoord) {
        rep_.error(pw.begin, pw.end, "the switch distance L is out of range (magnitude above 1e9)", "gcode-range");
        ok = false;
        continue;
      }
    }
    if (h == 0) continue;   // H0: no switch action
    SwitchPoint& s = e.switches[e.switchCount++];
    s.sw = static_cast<int16_t>(h);
    s.relative = rel;
    s.pos = p;
  }
  return ok;
}

void Decoder::decodeBlock(const Block& b, ElementQueue& out) {
  BlockCmds c;
  if (b.gCount && !collectCommands(b, c)) return;
  if (c.motion.code < 0 && c.other.code < 0 && c.offset.code < 0) {
    // No command: axis words (or centre/radius words of a modal arc) continue
    // the modal travel command.
    uint32_t others = (c.plane.code == 16 ? kIJK : 0) | (b.has('M') ? B('K') | B('L') : 0);
    if (motion_ >= 0) {
      if (b.present & motionMask(motion_) & ~others) c.motion = Cmd{motion_, -1}, c.implied = true;
    } else if (b.present & kAxesMask) {
      const Word& w = b.words[b.at[lowestBit(b.present & kAxesMask)]];
      rep_.error(w.begin, w.end, "axis words without a travel command: write G0, G1, G2 ... in this or an earlier block",
                 "gcode-missing-word");
      return;
    }
  }
  if (!checkClaims(b, c)) return;
  if (!modalWords(b)) return;
  if (c.dist.code >= 0) incremental_ = c.dist.code == 91;
  if (c.centre.code >= 0) centreAbsolute_ = c.centre.code == 98;
  if (c.plane.code == 16) {
    if (b.present & kIJK) {
      Vec3 nv{0, 0, 0};
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        char l = "IJK"[k];
        if (!b.has(l)) continue;
        double v;
        if (!wordValue(b, l, v)) ok = false;
        else if (std::fabs(v) > kMaxCoord) {
          rep_.error(b.word(l).begin, b.word(l).end, "the normal component is out of range", "gcode-range");
          ok = false;
        } else {
          nv[k] = v;
        }
      }
      if (!ok) return;
      Vec3 nn = normalized(nv);
      if (norm(nn) == 0) {
        const Word& w = b.words[c.plane.word];
        rep_.error(w.begin, w.end, "G16 needs a plane normal I/J/K that is not zero", "gcode-range");
        return;
      }
      n_ = nn;
      // u: X projected into the plane (Y if X is the normal), v = n x u.
      Vec3 ref = std::fabs(nn[0]) > 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
      u_ = normalized(ref - dot(ref, nn) * nn);
      v_ = cross(n_, u_);
      plane_ = Plane::Free;
    }
  } else if (c.plane.code >= 0) {
    setPlane(c.plane.code);
  }

  // Variables.
  if (c.other.code == 36 || c.other.code == 37) {
    const Word& gw = b.words[c.other.word];
    if (!b.has('D')) {
      rep_.error(gw.begin, gw.end, gName(c.other.code) + " needs the value D", "gcode-missing-word");
      return;
    }
    double d;
    if (!wordValue(b, 'D', d)) return;
    if (b.has('O')) {
      const Word& o = b.word('O');
      if (o.kind != WordKind::Variable) {
        rep_.error(o.begin, o.end, "O must name a variable: O$name$", "gcode-syntax");
        return;
      }
      std::string_view name = text_.substr(o.nameBegin, o.nameEnd - o.nameBegin);
      double v = d;
      if (c.other.code == 37) {
        Word plain = o;
        plain.negate = false;
        if (!resolve(b, plain, v)) return;
        v += d;
      }
      if (!vars_ || !vars_->write(name, v)) {
        rep_.error(o.begin, o.end, "cannot write the variable '$" + std::string(name) + "$'", "gcode-variable");
        return;
      }
    } else {
      counter_ = c.other.code == 36 ? d : counter_ + d;
      if (!std::isfinite(counter_) || std::fabs(counter_) > 1e15) {
        rep_.error(gw.begin, gw.end, "the decoder variable is out of range (" + formatApprox(counter_) + ")",
                   "gcode-range");
        counter_ = -1;
        return;
      }
    }
  }

  // Offsets (G53..G56): machine = program + offset.
  if (c.offset.code >= 0) {
    Pos vals{};
    uint32_t given = 0;
    bool ok = true;
    for (int a = 0; a < kAxisCount; ++a) {
      int8_t i = b.at[slotOf(kAxisLetters[a])];
      if (i < 0) continue;
      double v;
      if (!resolve(b, b.words[i], v)) ok = false;
      else if (std::fabs(v) > kMaxCoord) {
        rep_.error(b.words[i].begin, b.words[i].end, "offset out of range (magnitude above 1e9)", "gcode-range");
        ok = false;
      } else {
        vals[a] = v;
        given |= 1u << a;
      }
    }
    if (!ok) return;
    for (int a = 0; a < kAxisCount; ++a) {
      bool has = given & (1u << a);
      switch (c.offset.code) {
        case 53: offsetVec_[a] = 0; break;
        case 54: offsetVec_[a] = has ? vals[a] : 0; break;
        case 55: if (has) offsetVec_[a] += vals[a]; break;
        case 56: if (has) offsetVec_[a] = pos_[a] - vals[a]; break;
        default: break;
      }
    }
  }

  // Preprocessing marks for the next motion element.
  if (c.tool.code >= 0) {
    const Word& gw = b.words[c.tool.word];
    if (c.tool.code == 40) {
      if (toolSide_ != ToolSide::Off) marks_ |= MarkToolCorrEnd;
      toolSide_ = ToolSide::Off;
      toolRadius_ = 0;
      toolOnAt_ = 0;
    } else if (toolSide_ != ToolSide::Off) {
      rep_.error(gw.begin, gw.end, "tool radius correction is already on; end it with G40 before " + gName(c.tool.code),
                 "gcode-conflict")
          .note(rep_.loc(toolOnAt_ - 1), "switched on here");
      return;
    } else if (!b.has('D')) {
      rep_.error(gw.begin, gw.end, gName(c.tool.code) + " needs the tool radius D", "gcode-missing-word");
      return;
    } else {
      double d;
      if (!wordValue(b, 'D', d)) return;
      if (!(d >= 0) || d > kMaxCoord) {
        rep_.error(b.word('D').begin, b.word('D').end, "the tool radius D must be >= 0 and at most 1e9", "gcode-range");
        return;
      }
      toolSide_ = c.tool.code == 41 ? ToolSide::Left : ToolSide::Right;
      toolRadius_ = d;
      toolOnAt_ = gw.begin + 1;
      marks_ |= c.tool.code == 41 ? MarkToolCorrLeft : MarkToolCorrRight;
    }
  }
  if (c.smooth.code >= 0) {
    const Word& gw = b.words[c.smooth.word];
    if (c.smooth.code == 50) {
      if (smoothing_ != Smoothing::Off) marks_ |= MarkSmoothEnd;
      smoothing_ = Smoothing::Off;
      smoothDist_ = 0;
    } else if (!b.has('D')) {
      rep_.error(gw.begin, gw.end, gName(c.smooth.code) + " needs the corner distance D", "gcode-missing-word");
      return;
    } else {
      double d;
      if (!wordValue(b, 'D', d)) return;
      if (!(d >= 0) || d > kMaxCoord) {
        rep_.error(b.word('D').begin, b.word('D').end, "the corner distance D must be >= 0 and at most 1e9",
                   "gcode-range");
        return;
      }
      smoothing_ = c.smooth.code == 51 ? Smoothing::Smooth : Smoothing::Round;
      smoothDist_ = d;
      marks_ |= c.smooth.code == 51 ? MarkSmoothStart : MarkRoundStart;
    }
  }
  if (c.loop.code >= 0) {
    if (c.loop.code == 60) {
      if (loopAvoid_) marks_ |= MarkLoopAvoidEnd;
      loopAvoid_ = false;
    } else {
      loopAvoid_ = true;
      marks_ |= MarkLoopAvoidStart;
    }
  }

  // The element of the block.
  bool moved = false;
  if (c.motion.code >= 0) {
    if (!c.implied) motion_ = c.motion.code;
    // An explicit travel command without its words only sets the mode.
    if ((b.present & motionMask(c.motion.code)) && !decodeMotion(b, c.motion, out, moved)) return;
  } else if (c.other.code == 4) {
    const Word& gw = b.words[c.other.word];
    if (!b.has('T')) {
      rep_.error(gw.begin, gw.end, "G4 needs the dwell time T (seconds)", "gcode-missing-word");
      return;
    }
    double t;
    if (!wordValue(b, 'T', t)) return;
    if (!(t >= 0) || t > kMaxDwell) {
      rep_.error(b.word('T').begin, b.word('T').end, "the dwell time T must be >= 0 and at most 1e6 s", "gcode-range");
      return;
    }
    Element e;
    startElement(b, c.other, MoveType::Dwell, e);
    e.dwell = t;
    emit(out, e);
  } else if (c.other.code == 92) {
    if (b.present & kAxesMask) {
      Pos tgt;
      if (!target(b, false, tgt)) return;
      Element e;
      startElement(b, c.other, MoveType::InitPos, e);
      e.end = tgt;
      emit(out, e);
      pos_ = tgt;
    }
  } else if (c.other.code == 75) {
    Element e;
    startElement(b, c.other, MoveType::Sync, e);
    e.m = 65534;
    emit(out, e);
    syncQueued_ = true;
  }

  if (b.switchCount && !moved) {
    const Word& w = b.words[b.switches[0].h];
    rep_.error(w.begin, w.end, "switch points (H) need a move in the same block", "gcode-missing-word");
    return;
  }

  if (b.has('M')) {
    double m;
    if (!wordValue(b, 'M', m)) return;
    double k = 0, l = 0;
    if (b.has('K') && !wordValue(b, 'K', k)) return;
    if (b.has('L') && !wordValue(b, 'L', l)) return;
    Element e;
    Cmd mc{-1, b.at[slotOf('M')]};
    startElement(b, mc, MoveType::MCommand, e);
    e.m = static_cast<uint16_t>(m);
    e.k = k;
    e.l = l;
    emit(out, e);
  }

  // Jumps come last: the block's own element is queued first.
  if (c.other.code == 20 || c.other.code == 25) {
    const Word& gw = b.words[c.other.word];
    if (!b.has('L')) {
      rep_.error(gw.begin, gw.end, gName(c.other.code) + " needs the jump target L (a block number or L?label)",
                 "gcode-missing-word");
      return;
    }
    double cond = counter_;
    if (b.has('K') && !wordValue(b, 'K', cond)) return;
    if (cond == 0) return;
    uint32_t off, line;
    if (!findTarget(b, b.word('L'), off, line)) return;
    if (jumps_ >= opts_.maxJumps) {
      rep_.error(gw.begin, gw.end, "more than " + std::to_string(opts_.maxJumps) +
                                       " jumps taken: the program loops without end (the decoder's jump limit)",
                 "gcode-loop-limit");
      finished_ = true;
      out.endOfList = true;
      return;
    }
    ++jumps_;
    jumped_ = true;
    jumpOffset_ = off;
    jumpLine_ = line;
  }
}

bool Decoder::findTarget(const Block& b, const Word& w, uint32_t& offset, uint32_t& line) {
  auto scanOne = [&] {
    uint32_t next = quietParser_.parse(indexedTo_, indexedLine_, scan_);
    indexBlock(scan_);
    indexedTo_ = next;
    ++indexedLine_;
  };
  if (w.kind == WordKind::LabelRef) {
    int32_t key = static_cast<int32_t>(w.value);
    const BlockIndex::Entry* e = labels_.find(key);
    while (!e && indexedTo_ < text_.size()) {
      scanOne();
      e = labels_.find(key);
    }
    if (!e) {
      rep_.error(w.begin, w.end, "jump to an unknown label: no block has L!" + std::to_string(key), "gcode-jump",
                 SmcError::JumpToUnknownLine);
      return false;
    }
    if (e->offset <= b.begin) {
      rep_.error(w.begin, w.end, "L?" + std::to_string(key) + " jumps backwards to L!" + std::to_string(key) +
                                     " on line " + std::to_string(e->line) + "; label jumps only go forward",
                 "gcode-jump", SmcError::JumpToUnknownLine);
      return false;
    }
    offset = e->offset;
    line = e->line;
    return true;
  }
  double v;
  if (!resolve(b, w, v)) return false;
  if (v != std::trunc(v) || v < 0 || v > 2147483647.0) {
    rep_.error(w.begin, w.end, "the jump target L is a block number (an integer from 0 to 2147483647)", "gcode-jump",
               SmcError::JumpToUnknownLine);
    return false;
  }
  int32_t key = static_cast<int32_t>(v);
  const BlockIndex::Entry* e = index_.find(key);
  while (!e && indexedTo_ < text_.size()) {
    scanOne();
    e = index_.find(key);
  }
  if (!e) {
    rep_.error(w.begin, w.end, "jump to an unknown block: no block has N" + std::to_string(key), "gcode-jump",
               SmcError::JumpToUnknownLine);
    return false;
  }
  offset = e->offset;
  line = e->line;
  return true;
}

// ---------------------------------------------------------------- motion

bool Decoder::centreOf(const Block& b, Vec3& c, bool& any) {
  Vec3 s = xyz(pos_);
  c = s;
  any = false;
  for (int k = 0; k < 3; ++k) {
    char l = "IJK"[k];
    if (!b.has(l)) continue;
    double v;
    if (!wordValue(b, l, v)) return false;
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(b.word(l).begin, b.word(l).end, std::string(1, l) + " is out of range (magnitude above 1e9)",
                 "gcode-range");
      return false;
    }
    c[k] = centreAbsolute_ ? v + offsetVec_[k] : s[k] + v;
    any = true;
  }
  return true;
}

bool Decoder::buildArc(const Block& b, const Cmd& cmd, const Pos& tgtIn, Element& e) {
  const int code = cmd.code;
  const bool ccw = code == 3;
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  const bool hasR = b.has('R'), hasT = b.has('T'), hasC = b.present & kIJK;
  if (hasR && (hasC || hasT)) {
    const Word& w = b.word('R');
    rep_.error(w.begin, w.end, hasC ? "the radius R and the centre I/J/K cannot both describe an arc"
                                    : "the radius R and the sweep T cannot both describe an arc",
               "gcode-conflict");
    return false;
  }
  if (!hasR && !hasC) {
    if (hasT) {
      const Word& w = b.word('T');
      rep_.error(w.begin, w.end, "the sweep T needs the arc's centre I/J/K", "gcode-missing-word");
    } else {
      rep_.error(cmdAt, cmdEnd,
                 gName(code) + " needs the centre (I/J/K), the radius R, or the centre and the sweep T",
                 "gcode-missing-word");
    }
    return false;
  }
  Pos tgt = tgtIn;
  const Vec3 S = xyz(pos_), n = n_, u = u_, v = v_;
  Vec3 T3 = xyz(tgt);
  double sweepDeg = 0;
  if (hasT) {
    uint32_t inPlane = plane_ == Plane::XY   ? B('X') | B('Y')
                       : plane_ == Plane::ZX ? B('Z') | B('X')
                       : plane_ == Plane::YZ ? B('Y') | B('Z')
                                             : B('X') | B('Y') | B('Z');
    if (b.present & inPlane) {
      const Word& w = b.words[b.at[lowestBit(b.present & inPlane)]];
      rep_.error(w.begin, w.end, "with a sweep T the end point follows from the centre and T; '" + slotName(w.slot) +
                                     "' cannot be given",
                 "gcode-conflict");
      return false;
    }
    if (!wordValue(b, 'T', sweepDeg)) return false;
    if (!(sweepDeg > 0) || sweepDeg > kMaxSweep) {
      const Word& w = b.word('T');
      rep_.error(w.begin, w.end, "the sweep T must be > 0 and at most 36000 degrees (is " + formatNumber(sweepDeg) + ")",
                 "gcode-range");
      return false;
    }
  }
  const double rise = dot(T3 - S, n);
  Vec3 Ep = T3 - rise * n;
  Vec3 C;
  if (hasR) {
    double r;
    if (!wordValue(b, 'R', r)) return false;
    const Word& rw = b.word('R');
    if (r == 0 || std::fabs(r) > kMaxCoord) {
      rep_.error(rw.begin, rw.end, "the radius R must not be 0 and at most 1e9 in magnitude", "gcode-range");
      return false;
    }
    Vec3 chord = Ep - S;
    double d = norm(chord), rr = std::fabs(r), half = 0.5 * d;
    if (d <= 1e-12 * std::max(1.0, rr)) {
      rep_.error(rw.begin, rw.end, "a full circle cannot be given by its radius; program the centre with I/J/K",
                 "gcode-arc");
      return false;
    }
    double h = 0;
    if (rr < half) {
      if (half - rr > 1e-9 * std::max(1.0, half)) {
        rep_.error(rw.begin, rw.end, "the radius " + formatNumber(rr) + " is smaller than half the chord (" +
                                         formatApprox(half) + "): no arc of this radius joins the points",
                   "gcode-arc");
        return false;
      }
    } else {
      h = std::sqrt(rr * rr - half * half);
    }
    Vec3 w = normalized(cross(n, chord));
    bool shortArc = r > 0;
    double sgn = (ccw == shortArc) ? 1.0 : -1.0;
    C = S + 0.5 * chord + (sgn * h) * w;
  } else {
    bool any;
    if (!centreOf(b, C, any)) return false;
    C = C - dot(C - S, n) * n;   // into the plane through the start
  }
  Vec3 s0 = S - C;
  double r0 = norm(s0);
  if (!(r0 > 1e-12)) {
    rep_.error(cmdAt, cmdEnd, "the arc's centre is its start point (radius 0)", "gcode-arc");
    return false;
  }
  double a0 = std::atan2(dot(s0, v), dot(s0, u));
  double sweep;
  if (hasT) {
    sweep = (ccw ? 1 : -1) * sweepDeg * kPi / 180;
    double a1 = a0 + sweep;
    Vec3 E = C + (r0 * std::cos(a1)) * u + (r0 * std::sin(a1)) * v + rise * n;
    tgt[AxX] = E[0];
    tgt[AxY] = E[1];
    tgt[AxZ] = E[2];
  } else {
    bool full = norm(Ep - S) <= 1e-9 * std::max(1.0, r0);
    if (!full && !hasR) {
      double r1 = norm(Ep - C);
      double diff = std::fabs(r0 - r1), rel = diff / std::max(r0, r1);
      if (rel > 0.1) {
        rep_.error(cmdAt, cmdEnd,
                   "the end point is not on the arc: it is " + formatApprox(r1) + " from the centre, the start " +
                       formatApprox(r0) + " (the decoder corrects differences up to 10%)",
                   "gcode-arc");
        return false;
      }
      if (diff > 1e-12 * std::max(r0, r1)) {
        // Move the centre onto the chord's perpendicular bisector.
        Vec3 chord = Ep - S, M = S + 0.5 * chord;
        Vec3 w = normalized(cross(n, chord));
        Vec3 C2 = M + dot(C - M, w) * w;
        if (rel > 1e-3)
          rep_.warning(cmdAt, cmdEnd,
                       "arc centre moved by " + formatApprox(norm(C2 - C)) +
                           " to fit the end point (start and end radii differ by " + formatApprox(rel * 100) + "%)",
                       "gcode-arc-centre");
        C = C2;
        s0 = S - C;
        r0 = norm(s0);
        a0 = std::atan2(dot(s0, v), dot(s0, u));
      }
    }
    if (full) {
      sweep = ccw ? 2 * kPi : -2 * kPi;
    } else {
      Vec3 e1 = Ep - C;
      double a1 = std::atan2(dot(e1, v), dot(e1, u));
      sweep = sweepOf(a1 - a0, ccw);
    }
  }
  e.type = ccw ? MoveType::Cclw : MoveType::Clw;
  e.end = tgt;
  e.arc = ArcGeo{C, u, v, n, r0, a0, sweep, rise};
  return true;
}

bool Decoder::buildEllipse(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e, bool& asLine) {
  const int code = cmd.code;
  const bool ccw = code == 9;
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  asLine = false;
  if (!b.has('I') && !b.has('J')) {
    rep_.error(cmdAt, cmdEnd, gName(code) + " needs the ellipse's centre I/J", "gcode-missing-word");
    return false;
  }
  const Vec3 S = xyz(pos_), T3 = xyz(tgt);
  double c[2] = {S[0], S[1]};
  for (int k = 0; k < 2; ++k) {
    char l = "IJ"[k];
    if (!b.has(l)) continue;
    double v;
    if (!wordValue(b, l, v)) return false;
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(b.word(l).begin, b.word(l).end, std::string(1, l) + " is out of range (magnitude above 1e9)",
                 "gcode-range");
      return false;
    }
    c[k] = centreAbsolute_ ? v + offsetVec_[k] : S[k] + v;
  }
  double kdeg = 0;
  if (b.has('K')) {
    if (!wordValue(b, 'K', kdeg)) return false;
    if (std::fabs(kdeg) > kMaxSweep) {
      rep_.error(b.word('K').begin, b.word('K').end, "the main axis direction K is out of range (|K| <= 36000 degrees)",
                 "gcode-range");
      return false;
    }
  }
  double ratio = 0;
  if (b.has('R')) {
    if (!wordValue(b, 'R', ratio)) return false;
    if (!(ratio > 0) || ratio > 1) {
      rep_.error(b.word('R').begin, b.word('R').end,
                 "the axis ratio R must be in (0, 1] (is " + formatNumber(ratio) + ")", "gcode-range");
      return false;
    }
  }
  double phi = kdeg * kPi / 180;
  Vec3 e1{std::cos(phi), std::sin(phi), 0}, e2{-std::sin(phi), std::cos(phi), 0};
  Vec3 C{c[0], c[1], S[2]};
  Vec3 s = S - C, t = T3 - C;
  t[2] = 0;
  double x0 = dot(s, e1), y0 = dot(s, e2), x1 = dot(t, e1), y1 = dot(t, e2);
  double scale = std::max(x0 * x0 + y0 * y0, x1 * x1 + y1 * y1);
  if (!(scale > 1e-24)) {
    rep_.error(cmdAt, cmdEnd, "the ellipse's start and end are its centre", "gcode-arc");
    return false;
  }
  double tol = 1e-9 * scale, a = 0, bb = 0;
  if (std::fabs(y0 * y0 - y1 * y1) <= tol) {
    // Both points equally far from the main axis: only R decides (if they
    // are also equally far from the second axis).
    if (std::fabs(x0 * x0 - x1 * x1) <= tol) {
      if (!(ratio > 0)) {
        rep_.error(cmdAt, cmdEnd,
                   "the ellipse is not defined by its end points, centre and axis direction: give the axis ratio R",
                   "gcode-missing-word");
        return false;
      }
      a = std::sqrt(x0 * x0 + (y0 * y0) / (ratio * ratio));
      bb = ratio * a;
    }
  } else {
    double det = x0 * x0 * y1 * y1 - x1 * x1 * y0 * y0;
    double p = (y1 * y1 - y0 * y0) / det, q = (x0 * x0 - x1 * x1) / det;
    if (p > 0 && q > 0 && std::isfinite(p) && std::isfinite(q)) {
      a = 1 / std::sqrt(p);
      bb = 1 / std::sqrt(q);
    }
  }
  if (!(a > 0 && bb > 0) || !std::isfinite(a) || !std::isfinite(bb) || a > kMaxPosition || bb > kMaxPosition) {
    rep_.warning(cmdAt, cmdEnd,
                 "no ellipse with this centre and axis direction passes through both points; the move is a line",
                 "gcode-ellipse-line");
    asLine = true;
    return true;
  }
  double p0 = std::atan2(y0 / bb, x0 / a), p1 = std::atan2(y1 / bb, x1 / a);
  bool full = std::hypot(T3[0] - S[0], T3[1] - S[1]) <= 1e-9 * std::sqrt(scale);
  double sweep = full ? (ccw ? 2 * kPi : -2 * kPi) : sweepOf(p1 - p0, ccw);
  e.type = ccw ? MoveType::EllCclw : MoveType::EllClw;
  e.end = tgt;
  e.ellipse = EllipseGeo{C, e1, a, bb, phi, p0, sweep, T3[2] - S[2]};
  return true;
}

bool Decoder::buildParabola(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e) {
  const uint32_t cmdAt = cmdBegin(b, cmd), cmdEnd = cmdStop(b, cmd);
  if (!b.has('I') && !b.has('J')) {
    rep_.error(cmdAt, cmdEnd, "G6 needs the parabola's vertex I/J", "gcode-missing-word");
    return false;
  }
  const Vec3 S = xyz(pos_), T3 = xyz(tgt);
  Vec3 V = S;
  for (int k = 0; k < 2; ++k) {
    char l = "IJ"[k];
    if (!b.has(l)) continue;
    double v;
    if (!wordValue(b, l, v)) return false;
    if (std::fabs(v) > kMaxCoord) {
      rep_.error(b.word(l).begin, b.word(l).end, std::string(1, l) + " is out of range (magnitude above 1e9)",
                 "gcode-range");
      return false;
    }
    V[k] = centreAbsolute_ ? v + offsetVec_[k] : S[k] + v;
  }
  V[2] = 0.5 * (S[2] + T3[2]);
  if (std::hypot(T3[0] - S[0], T3[1] - S[1]) <= 1e-12 * std::max(1.0, norm(S))) {
    rep_.error(cmdAt, cmdEnd, "a parabola needs different start and end points in X/Y", "gcode-arc");
    return false;
  }
  Vec3 ctrl = 2.0 * V - 0.5 * (S + T3);
  ctrl[2] = V[2];
  e.type = MoveType::Parabola;
  e.end = tgt;
  e.parabola = ParabolaGeo{V, ctrl};
  return true;
}

bool Decoder::decodeMotion(const Block& b, const Cmd& cmd, ElementQueue& out, bool& produced) {
  const int code = cmd.code;
  produced = false;
  if ((code == 5 || code == 6 || code == 8 || code == 9) && plane_ != Plane::XY) {
    rep_.error(cmdBegin(b, cmd), cmdStop(b, cmd),
               gName(code) + " works in the XY plane only (G17); the active plane is " + toString(plane_),
               "gcode-plane", SmcError::ObjectNot3D);
    return false;
  }
  Pos tgt;
  if (!target(b, incremental_, tgt)) return false;
  Element e;
  startElement(b, cmd, code == 0 ? MoveType::LinPos : MoveType::Lin, e);
  e.end = tgt;
  switch (code) {
    case 2:
    case 3:
      if (!buildArc(b, cmd, tgt, e)) return false;
      break;
    case 6:
      if (!buildParabola(b, cmd, tgt, e)) return false;
      break;
    case 8:
    case 9: {
      bool asLine;
      if (!buildEllipse(b, cmd, tgt, e, asLine)) return false;
      break;
    }
    case 5:
    case 10: {
      uint8_t dims = code == 5 ? 2 : 3;
      Vec3 S = xyz(pos_), T3 = xyz(tgt);
      Vec3 ch = T3 - S;
      if (dims == 2) ch[2] = 0;
      double L = norm(ch);
      if (!(L > 0)) {
        if (tgt == pos_) return true;   // no move
        rep_.error(cmdBegin(b, cmd), cmdStop(b, cmd),
                   dims == 2 ? "a G5 spline needs a move in X/Y (G10 is the 3D spline)" : "a spline needs a move in X/Y/Z",
                   "gcode-arc");
        return false;
      }
      Vec3 t0{0, 0, 0};
      if (havePending_) t0 = T3 - xyz(pending_.start);
      else if (lastTangentValid_) t0 = lastTangent_;
      if (dims == 2) t0[2] = 0;
      t0 = normalized(t0);
      Vec3 cd = normalized(ch);
      if (norm(t0) == 0) t0 = cd;
      e.type = MoveType::Spline;
      e.spline = SplineGeo{t0, cd, L, dims};
      break;
    }
    default:   // 0, 1: lines
      if (tgt == pos_) return true;   // no move, no element
      break;
  }
  if (e.type != MoveType::LinPos && e.vel == 0 && !feedWarned_) {
    feedWarned_ = true;
    rep_.warning(cmdBegin(b, cmd), cmdStop(b, cmd), "no path velocity: F is not programmed yet and the decoder has no default velocity",
                 "gcode-no-feed");
  }
  if (!switchPoints(b, e)) return false;
  e.marks = marks_;
  marks_ = 0;
  if (e.type != MoveType::Spline) e.length = pathLength(e);
  pos_ = e.end;
  emit(out, e);
  produced = true;
  return true;
}

// ---------------------------------------------------------------- output

void Decoder::emit(ElementQueue& out, const Element& e) {
  if (e.type == MoveType::Spline) {
    if (havePending_) flushPending(out, &e);
    pending_ = e;
    havePending_ = true;
    return;
  }
  if (havePending_) flushPending(out, &e);
  Element& slot = out.push();
  slot = e;
  slot.objNo = ++objNo_;
  if (isToolPath(e.type)) {
    lastTangent_ = endTangent(slot);
    lastTangentValid_ = norm(lastTangent_) > 0;
  } else {
    lastTangentValid_ = false;
  }
}

void Decoder::flushPending(ElementQueue& out, const Element* next) {
  Element& p = pending_;
  Vec3 chord = xyz(p.end) - xyz(p.start);
  if (p.spline.dims == 2) chord[2] = 0;
  Vec3 t = normalized(chord);
  if (next) {
    Vec3 c{0, 0, 0};
    if (next->type == MoveType::Spline) c = xyz(next->end) - xyz(p.start);
    else if (isToolPath(next->type)) c = startTangent(*next);
    if (p.spline.dims == 2) c[2] = 0;
    Vec3 tn = normalized(c);
    if (norm(tn) > 0) t = tn;
  }
  p.spline.t1 = t;
  p.length = pathLength(p);
  Element& slot = out.push();
  slot = p;
  slot.objNo = ++objNo_;
  lastTangent_ = endTangent(slot);
  lastTangentValid_ = norm(lastTangent_) > 0;
  havePending_ = false;
}

// ---------------------------------------------------------------- one-shot

std::vector<Element> decodeAll(const SourceManager& sm, uint32_t file, DiagnosticsEngine& diags,
                               const DecoderOptions& opts, VariableAccess* vars) {
  std::vector<Element> result;
  Decoder dec(sm, file, diags, opts, vars);
  ElementQueue q(64);
  for (;;) {
    StepResult r = dec.step(q);
    while (!q.empty()) {
      result.push_back(q.front());
      q.pop();
    }
    if (r.status == StepStatus::Finished) break;
  }
  return result;
}

}  // namespace stc::cnc

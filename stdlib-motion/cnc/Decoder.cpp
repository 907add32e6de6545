#include "stdlib-motion/cnc/Decoder.h"

#include <algorithm>
#include <cmath>

#include "stdlib-motion/cnc/DecoderInternal.h"
#include "stdlib-motion/cnc/Geometry.h"

namespace stc::cnc {

using namespace detail;

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
  uint32_t obj0 = objNo_;
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
  r.elements = objNo_ - obj0;
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
    if (std::string why = vars_->problem(); !why.empty()) {
      rep_.error(w.begin, w.end, "cannot read the variable '$" + std::string(name) + "$': " + why, "gcode-variable");
      return false;
    }
    const std::string near = vars_->suggest(name);
    rep_.error(w.begin, w.end, "unknown variable '$" + std::string(name) + "$'" + (near.empty() ? "" : "; did you mean '$" + near + "$'?"),
               "gcode-variable");
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
  if (!checkClaims(b, c) || !modalWords(b)) return;
  if (c.dist.code >= 0) incremental_ = c.dist.code == 91;
  if (c.centre.code >= 0) centreAbsolute_ = c.centre.code == 98;
  if (c.plane.code == 16) {
    if (!planeNormal(b, c)) return;
  } else if (c.plane.code >= 0) {
    setPlane(c.plane.code);
  }
  if ((c.other.code == 36 || c.other.code == 37) && !variable(b, c)) return;
  if (c.offset.code >= 0 && !offsets(b, c)) return;
  if (!preprocessing(b, c)) return;

  // The element of the block, then its M function, then a jump.
  bool moved = false;
  if (c.motion.code >= 0) {
    if (!c.implied) motion_ = c.motion.code;
    // An explicit travel command without its words only sets the mode.
    if ((b.present & motionMask(c.motion.code)) && !decodeMotion(b, c.motion, out, moved)) return;
  } else if (c.other.code >= 0 && !otherElement(b, c, out)) {
    return;
  }
  if (b.switchCount && !moved) {
    const Word& w = b.words[b.switches[0].h];
    rep_.error(w.begin, w.end, "switch points (H) need a move in the same block", "gcode-missing-word");
    return;
  }
  if (b.has('M') && !mFunction(b, out)) return;
  if (c.other.code == 20 || c.other.code == 25) jump(b, c, out);
}

// G16 I J K: the plane normal; u is X projected into the plane (Y if X is
// within 26 degrees of the normal), v = n x u.
bool Decoder::planeNormal(const Block& b, const BlockCmds& c) {
  if (!(b.present & kIJK)) return true;   // G16 alone keeps the plane
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
  if (!ok) return false;
  Vec3 nn = normalized(nv);
  if (norm(nn) == 0) {
    const Word& w = b.words[c.plane.word];
    rep_.error(w.begin, w.end, "G16 needs a plane normal I/J/K that is not zero", "gcode-range");
    return false;
  }
  n_ = nn;
  Vec3 ref = std::fabs(nn[0]) > 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  u_ = normalized(ref - dot(ref, nn) * nn);
  v_ = cross(n_, u_);
  plane_ = Plane::Free;
  return true;
}

// G36 / G37 [O$var$] D.
bool Decoder::variable(const Block& b, const BlockCmds& c) {
  const Word& gw = b.words[c.other.word];
  if (!b.has('D')) {
    rep_.error(gw.begin, gw.end, gName(c.other.code) + " needs the value D", "gcode-missing-word");
    return false;
  }
  double d;
  if (!wordValue(b, 'D', d)) return false;
  if (b.has('O')) {
    const Word& o = b.word('O');
    if (o.kind != WordKind::Variable) {
      rep_.error(o.begin, o.end, "O must name a variable: O$name$", "gcode-syntax");
      return false;
    }
    std::string_view name = text_.substr(o.nameBegin, o.nameEnd - o.nameBegin);
    double v = d;
    if (c.other.code == 37) {
      Word plain = o;
      plain.negate = false;
      if (!resolve(b, plain, v)) return false;
      v += d;
    }
    if (!vars_ || !vars_->write(name, v)) {
      const std::string why = vars_ ? vars_->problem() : std::string("no variable source was given to the decoder");
      rep_.error(o.begin, o.end, "cannot write the variable '$" + std::string(name) + "$'" + (why.empty() ? "" : ": " + why),
                 "gcode-variable");
      return false;
    }
  } else {
    counter_ = c.other.code == 36 ? d : counter_ + d;
    if (!std::isfinite(counter_) || std::fabs(counter_) > 1e15) {
      rep_.error(gw.begin, gw.end, "the decoder variable is out of range (" + formatApprox(counter_) + ")",
                 "gcode-range");
      counter_ = -1;
      return false;
    }
  }
  return true;
}

// G53..G56: machine = program + offset.
bool Decoder::offsets(const Block& b, const BlockCmds& c) {
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
  if (!ok) return false;
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
  return true;
}

// G40..G42, G50..G52, G60/G61: modal state and marks for the next motion element.
bool Decoder::preprocessing(const Block& b, const BlockCmds& c) {
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
      return false;
    } else if (!b.has('D')) {
      rep_.error(gw.begin, gw.end, gName(c.tool.code) + " needs the tool radius D", "gcode-missing-word");
      return false;
    } else {
      double d;
      if (!wordValue(b, 'D', d)) return false;
      if (!(d >= 0) || d > kMaxCoord) {
        rep_.error(b.word('D').begin, b.word('D').end, "the tool radius D must be >= 0 and at most 1e9", "gcode-range");
        return false;
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
      return false;
    } else {
      double d;
      if (!wordValue(b, 'D', d)) return false;
      if (!(d >= 0) || d > kMaxCoord) {
        rep_.error(b.word('D').begin, b.word('D').end, "the corner distance D must be >= 0 and at most 1e9",
                   "gcode-range");
        return false;
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
  return true;
}

// G4, G92, G75 (G20/G25/G36/G37 have no element).
bool Decoder::otherElement(const Block& b, const BlockCmds& c, ElementQueue& out) {
  if (c.other.code == 4) {
    const Word& gw = b.words[c.other.word];
    if (!b.has('T')) {
      rep_.error(gw.begin, gw.end, "G4 needs the dwell time T (seconds)", "gcode-missing-word");
      return false;
    }
    double t;
    if (!wordValue(b, 'T', t)) return false;
    if (!(t >= 0) || t > kMaxDwell) {
      rep_.error(b.word('T').begin, b.word('T').end, "the dwell time T must be >= 0 and at most 1e6 s", "gcode-range");
      return false;
    }
    Element e;
    startElement(b, c.other, MoveType::Dwell, e);
    e.dwell = t;
    emit(out, e);
  } else if (c.other.code == 92) {
    if (b.present & kAxesMask) {
      Pos tgt;
      if (!target(b, false, tgt)) return false;
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
  return true;
}

bool Decoder::mFunction(const Block& b, ElementQueue& out) {
  double m;
  if (!wordValue(b, 'M', m)) return false;
  double k = 0, l = 0;
  if (b.has('K') && !wordValue(b, 'K', k)) return false;
  if (b.has('L') && !wordValue(b, 'L', l)) return false;
  Element e;
  Cmd mc{-1, b.at[slotOf('M')]};
  startElement(b, mc, MoveType::MCommand, e);
  e.m = static_cast<uint16_t>(m);
  e.k = k;
  e.l = l;
  emit(out, e);
  return true;
}

// G20 / G25: the jump is taken after the block's elements are queued.
void Decoder::jump(const Block& b, const BlockCmds& c, ElementQueue& out) {
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

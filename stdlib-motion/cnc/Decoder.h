// The G-code decoder: a modal state machine that turns the blocks of a
// DIN 66025 program (Moons / CODESYS SoftMotion CNC dialect, and the Leadshine
// subset) into path elements (docs/cnc.md).
//
//  - Streaming: step() decodes blocks until the output queue is nearly full, a
//    block budget is spent, a G75 asks to wait for the interpolator, or the
//    program ends; the next call resumes where it stopped.  This is how the
//    SMC_NCDecoder block runs in a slow task and stops when its queue is full.
//  - Memory: the decoder's state is fixed; the output is bounded by the queue's
//    capacity; the only growing structure is the index of block numbers and
//    jump labels (16-32 bytes per numbered block), which jumps and the
//    duplicate-N check need.  Blocks are parsed into a reused fixed-size Block:
//    nothing is allocated per block.
//  - Errors are reported through the DiagnosticsEngine at file:line:col (the
//    same rendering as ST errors); a block with an error produces no element
//    and decoding goes on (several errors per run) unless stopAtFirstError.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/BlockIndex.h"
#include "stdlib-motion/cnc/Element.h"
#include "stdlib-motion/cnc/Parser.h"

namespace stc::cnc {

// $name$ references: the caller's variables (IEC variables of the project,
// SMC_VARLIST).  Names are passed as written between the dollars.
class VariableAccess {
public:
  virtual ~VariableAccess() = default;
  // The variable's value; false if there is no such variable.
  virtual bool read(std::string_view name, double& value) = 0;
  // G36/G37 O$name$: stores a value; false if the variable cannot be written.
  virtual bool write(std::string_view name, double value) = 0;
  // A known name close to an unknown one, for "did you mean" (empty: none).
  virtual std::string suggest(std::string_view name) { return {}; }
  // Why the last read or write of a name that exists failed (its type, a CONSTANT, a value
  // the type cannot hold); empty when the name is simply unknown.
  virtual std::string problem() const { return {}; }
};

struct DecoderOptions {
  bool skipSlashBlocks = true;         // bStepSuppress: '/' blocks are skipped (else decoded)
  bool requireBlockNumbers = false;    // every block needs N (Leadshine files)
  Pos startPosition{};                 // piStartPosition, machine coordinates
  // F / E / E- until the program sets them; 0 = not set (the element carries 0).
  double defaultVel = 0, defaultAcc = 0, defaultDec = 0;
  // FF / EF / EF- of G0 until the program sets them; 0 = G0 uses F / E / E-.
  double defaultRapidVel = 0, defaultRapidAcc = 0, defaultRapidDec = 0;
  // Loop guard: taking more jumps (G20/G25) than this is an error that ends
  // decoding, so a G20 loop cannot hang the decoder or fill memory.
  uint32_t maxJumps = 1000000;
  bool stopAtFirstError = false;
};

// A bounded FIFO of elements (SMC_OUTQUEUE): the decoder pushes, the consumer
// pops.  Storage is allocated once, in the constructor.
class ElementQueue {
public:
  static constexpr size_t kMinCapacity = 4;   // one block can push 3 elements
  explicit ElementQueue(size_t capacity);
  size_t capacity() const { return slots_.size(); }
  size_t size() const { return size_; }
  size_t free() const { return slots_.size() - size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == slots_.size(); }
  // A cleared slot at the back (the queue must not be full).
  Element& push();
  const Element& front() const { return slots_[read_]; }
  const Element& operator[](size_t i) const { return slots_[(read_ + i) % slots_.size()]; }
  void pop();
  void clear();
  bool endOfList = false;   // set by the decoder after the last element

private:
  std::vector<Element> slots_;
  size_t read_ = 0, size_ = 0;
};

enum class StepStatus : uint8_t {
  Progress,    // the block budget is spent; call again
  QueueFull,   // the queue has no room for another block's elements; drain it, call again
  Sync,        // a G75 element was queued: call again once the interpolator has caught up
  Finished,    // the program ended (or decoding stopped at an error): endOfList is set
};
const char* toString(StepStatus s);

struct StepResult {
  StepStatus status = StepStatus::Progress;
  uint32_t blocks = 0;     // blocks decoded by this call
  uint32_t elements = 0;   // elements pushed by this call
};

class Decoder {
public:
  // `sm` must outlive the decoder and hold `file` (the program text).
  Decoder(const SourceManager& sm, uint32_t file, DiagnosticsEngine& diags, const DecoderOptions& opts = {},
          VariableAccess* vars = nullptr);

  // Decodes at most maxBlocks blocks into `out` (see StepStatus).
  StepResult step(ElementQueue& out, uint32_t maxBlocks = UINT32_MAX);
  // Starts again from the first block with the initial state.
  void reset();

  bool finished() const { return finished_; }
  unsigned errorCount() const { return rep_.errors(); }
  SmcError firstError() const { return rep_.firstError(); }
  // Machine position after the last decoded block.
  const Pos& position() const { return pos_; }
  // The line of the last decoded block (iLineNumberDecoded), 0 before the first.
  uint32_t lastLine() const { return lastLine_; }
  double internalVariable() const { return counter_; }
  uint64_t jumpsTaken() const { return jumps_; }
  std::string_view programName() const { return name_; }
  // Bytes of the block-number index (the only memory that grows with the program).
  size_t indexBytes() const { return index_.bytes() + labels_.bytes(); }

private:
  struct Cmd {
    int code = -1;   // G code, -1 none
    int word = -1;   // index of its word in the block
  };
  struct BlockCmds {
    Cmd motion, other, offset, plane, dist, centre, tool, smooth, loop;
    bool implied = false;    // motion from the modal state
  };

  void indexBlock(const Block& b);
  bool findTarget(const Block& b, const Word& w, uint32_t& offset, uint32_t& line);
  void decodeBlock(const Block& b, ElementQueue& out);
  bool planeNormal(const Block& b, const BlockCmds& c);
  bool variable(const Block& b, const BlockCmds& c);
  bool offsets(const Block& b, const BlockCmds& c);
  bool preprocessing(const Block& b, const BlockCmds& c);
  bool otherElement(const Block& b, const BlockCmds& c, ElementQueue& out);
  bool mFunction(const Block& b, ElementQueue& out);
  void jump(const Block& b, const BlockCmds& c, ElementQueue& out);
  bool collectCommands(const Block& b, BlockCmds& c);
  bool checkClaims(const Block& b, const BlockCmds& c);
  bool resolve(const Block& b, const Word& w, double& v);
  bool wordValue(const Block& b, char letter, double& v) { return resolve(b, b.word(letter), v); }
  bool modalWords(const Block& b);
  bool target(const Block& b, bool incremental, Pos& tgt);
  bool checkExclusiveAxes(const Block& b);
  void setPlane(int code);
  void startElement(const Block& b, const Cmd& cmd, MoveType type, Element& e) const;
  bool switchPoints(const Block& b, Element& e);
  bool decodeMotion(const Block& b, const Cmd& cmd, ElementQueue& out, bool& produced);
  bool buildArc(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e);
  bool buildEllipse(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e, bool& asLine);
  bool buildParabola(const Block& b, const Cmd& cmd, const Pos& tgt, Element& e);
  bool centreOf(const Block& b, Vec3& c, bool& any);
  bool centreWord(const Block& b, int k, double from, double& out);
  void emit(ElementQueue& out, const Element& e);
  void flushPending(ElementQueue& out, const Element* next);
  void finish(ElementQueue& out);
  uint32_t cmdBegin(const Block& b, const Cmd& c) const;
  uint32_t cmdStop(const Block& b, const Cmd& c) const;

  std::string_view text_;
  DecoderOptions opts_;
  VariableAccess* vars_;
  Reporter rep_;
  BlockParser parser_;
  Reporter quietRep_;
  BlockParser quietParser_;
  Block block_;          // reused for every block
  Block scan_;           // reused by index scans

  // Reading position.
  uint32_t offset_ = 0, line_ = 1, lastLine_ = 0;
  uint32_t indexedTo_ = 0, indexedLine_ = 1;   // blocks before this offset are indexed
  BlockIndex index_, labels_;
  bool sawBlock_ = false, finished_ = false;
  std::string_view name_;

  // Modal state.
  Pos pos_{}, offsetVec_{};
  int motion_ = -1;
  bool incremental_ = false, centreAbsolute_ = false;
  Plane plane_ = Plane::XY;
  Vec3 u_{1, 0, 0}, v_{0, 1, 0}, n_{0, 0, 1};
  double F_ = 0, E_ = 0, Ed_ = 0, FF_ = 0, EF_ = 0, EFd_ = 0, S_ = 0;
  ToolSide toolSide_ = ToolSide::Off;
  double toolRadius_ = 0;
  Smoothing smoothing_ = Smoothing::Off;
  double smoothDist_ = 0;
  bool loopAvoid_ = false;
  uint16_t marks_ = 0;          // for the next motion element
  uint16_t axesUsed_ = 0;
  uint32_t axisFirstUse_[kAxisCount] = {};   // offset + 1 of the first word of A/B/C/U/V/W
  uint32_t toolOnAt_ = 0;       // offset + 1 of the G41/G42 in force
  double counter_ = -1;         // the internal decoder variable
  bool feedWarned_ = false;

  // Output.
  uint32_t objNo_ = 0;
  bool havePending_ = false;    // a spline piece waiting for its successor
  Element pending_;
  bool lastTangentValid_ = false;
  Vec3 lastTangent_{};
  bool syncQueued_ = false;
  uint64_t jumps_ = 0;
  bool jumped_ = false;
  uint32_t jumpOffset_ = 0, jumpLine_ = 0;
};

// Decodes a whole program into a vector (tests, tools; a queue of 64 drained
// after every step).
std::vector<Element> decodeAll(const SourceManager& sm, uint32_t file, DiagnosticsEngine& diags,
                               const DecoderOptions& opts = {}, VariableAccess* vars = nullptr);

}  // namespace stc::cnc

// Loop avoidance (G61 ... G60) over path elements: the core of SMC_AvoidLoop (docs/cnc.md,
// "Loop avoidance").  A tool-corrected path crosses itself where the tool is too large for
// a detail of the contour (a notch narrower than the tool, a short element between two
// inside corners); running the loop would cut into the part.  Where a new element crosses
// one of the last kWindow elements, both are cut at the crossing and the loop between them
// is dropped.
//
// Streaming: push() in order, take the output (front/pop), finish() at the end.  While loop
// avoidance is on (Element::loopAvoid), the last kWindow elements are held back, because a
// later element may still cut them; elements without loopAvoid leave at once (after the
// held ones).  Crossings are found in the XY plane between lines and XY arcs; the other
// axes at the cut are the earlier element's.
#pragma once

#include <cstddef>
#include <deque>
#include <vector>

#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

class LoopAvoider {
public:
  static constexpr size_t kWindow = 32;

  void push(const Element& e);
  void finish();

  bool hasOutput() const { return !out_.empty(); }
  size_t outputSize() const { return out_.size(); }
  const Element& front() const { return out_.front(); }
  void pop() { out_.pop_front(); }
  size_t held() const { return window_.size(); }
  // Loops removed so far and elements dropped with them.
  size_t loopsRemoved() const { return loops_; }
  size_t elementsDropped() const { return dropped_; }

private:
  void flushWindow();
  bool cutLoop(Element& e);

  std::deque<Element> window_;
  std::deque<Element> out_;
  size_t loops_ = 0, dropped_ = 0;
};

// One-shot loop removal (tests and tools).
std::vector<Element> avoidLoopsAll(const std::vector<Element>& in);

}  // namespace stc::cnc

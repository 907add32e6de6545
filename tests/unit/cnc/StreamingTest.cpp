// Streaming: decoding a few blocks per call into a small queue gives exactly
// the one-shot result; a 10,000-block program decodes with bounded memory and
// without a heap allocation per block.
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>

#include "CncTestUtil.h"

// Counts heap allocations of this test binary (the decoder must not allocate
// per block).
static std::atomic<long> gAllocs{0};
void* operator new(std::size_t n) {
  ++gAllocs;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace stc::cnc::test {
namespace {

void expectSame(const Element& a, const Element& b) {
  EXPECT_EQ(a.objNo, b.objNo);
  EXPECT_EQ(a.line, b.line);
  EXPECT_EQ(a.column, b.column);
  EXPECT_EQ(a.blockNo, b.blockNo);
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.start, b.start);
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.vel, b.vel);
  EXPECT_EQ(a.acc, b.acc);
  EXPECT_EQ(a.dec, b.dec);
  EXPECT_EQ(a.length, b.length);
  EXPECT_EQ(a.marks, b.marks);
  EXPECT_EQ(a.m, b.m);
  EXPECT_EQ(a.switchCount, b.switchCount);
  // The geometry union, byte for byte (both come from the same computation).
  EXPECT_EQ(std::memcmp(&a.arc, &b.arc, sizeof(EllipseGeo) > sizeof(ArcGeo) ? sizeof(EllipseGeo) : sizeof(ArcGeo)), 0);
}

const char* kMixed =
    "% mixed\n"
    "N10 G0 X0 Y0 Z5 F200 E1000 E-1000\n"
    "N20 G41 D2\n"
    "N30 G1 X10 H1 L2 H-1 L-2\n"
    "N40 G5 X20 Y5\n"
    "N50 G5 X30 Y0\n"
    "N60 G2 X40 Y0 I5 J0\n"
    "N70 G3 X50 Y10 Z2 R10\n"
    "N80 M5 K1 L2\n"
    "N90 G40\n"
    "N100 G54 X100\n"
    "N110 G36 D3\n"
    "N120 G91 G1 X1 Y1\n"
    "N130 G37 D-1\n"
    "N140 G20 L120\n"
    "N150 G90 G10 X5 Y5 Z5\n"
    "N160 G4 T0.5\n"
    "N170 G98 G9 X10 Y0 I5 J0 K0\n"
    "N180 G6 X120 Y10 I2 J3\n"
    "N190 G92 X0 Y0\n"
    "N200 G1 X1\n";

TEST(CncStreaming, SmallStepsEqualOneShot) {
  Decoded once(kMixed);
  ASSERT_EQ(once.errors(), 0u) << once.all();
  ASSERT_GT(once.els.size(), 15u);
  for (uint32_t budget : {1u, 2u, 3u, 7u}) {
    for (size_t cap : {4u, 5u, 9u}) {
      SourceManager sm;
      DiagnosticsEngine diags(sm);
      Decoder dec(sm, sm.addBuffer("prog.cnc", kMixed), diags);
      ElementQueue q(cap);
      std::vector<Element> got;
      size_t maxSize = 0;
      int calls = 0;
      for (;;) {
        StepResult r = dec.step(q, budget);
        ++calls;
        maxSize = std::max(maxSize, q.size());
        // A slow consumer: one element per call.
        if (!q.empty()) {
          got.push_back(q.front());
          q.pop();
        }
        if (r.status == StepStatus::Finished) break;
        ASSERT_LT(calls, 10000);
      }
      while (!q.empty()) {
        got.push_back(q.front());
        q.pop();
      }
      EXPECT_LE(maxSize, std::max<size_t>(cap, ElementQueue::kMinCapacity));
      ASSERT_EQ(got.size(), once.els.size()) << "budget " << budget << " capacity " << cap;
      for (size_t i = 0; i < got.size(); ++i) expectSame(got[i], once.els[i]);
    }
  }
}

TEST(CncStreaming, StatusesQueueFullProgressSyncFinished) {
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  Decoder dec(sm, sm.addBuffer("p.cnc", "G1 X1 F1\nG1 X2\nG1 X3\nG75\nG1 X4\n"), diags);
  ElementQueue q(4);
  StepResult r = dec.step(q, 1);
  EXPECT_EQ(r.status, StepStatus::Progress);
  EXPECT_EQ(r.blocks, 1u);
  EXPECT_EQ(r.elements, 1u);
  r = dec.step(q);
  EXPECT_EQ(r.status, StepStatus::QueueFull);   // 2 queued, room for less than a block's worth
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(dec.lastLine(), 2u);
  q.pop();
  q.pop();
  r = dec.step(q);
  EXPECT_EQ(r.status, StepStatus::Sync);   // X3 and the G75 marker
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(q[1].type, MoveType::Sync);
  q.clear();
  r = dec.step(q);
  EXPECT_EQ(r.status, StepStatus::Finished);
  EXPECT_TRUE(q.endOfList);
  EXPECT_EQ(q.size(), 1u);
  EXPECT_TRUE(dec.finished());
  EXPECT_EQ(dec.step(q).status, StepStatus::Finished);
  // reset() decodes the same program again.
  dec.reset();
  q.clear();
  std::vector<Element> again;
  for (;;) {
    StepResult s = dec.step(q);
    while (!q.empty()) {
      again.push_back(q.front());
      q.pop();
    }
    if (s.status == StepStatus::Finished) break;
  }
  EXPECT_EQ(again.size(), 5u);
  EXPECT_EQ(dec.errorCount(), 0u);
}

TEST(CncStreaming, TenThousandBlocksWithBoundedMemory) {
  std::string prog;
  prog.reserve(400000);
  for (int i = 0; i < 10000; ++i) {
    char line[96];
    switch (i % 4) {
      case 0: std::snprintf(line, sizeof line, "N%d G1 X%d.5 Y%d Z1 F100 E500 E-500\n", i * 10, i % 97, i % 13); break;
      case 1: std::snprintf(line, sizeof line, "N%d G1 X%d Y%d.25 H3 L1\n", i * 10, i % 89, i % 7); break;
      case 2: std::snprintf(line, sizeof line, "N%d G2 X%d Y%d R500\n", i * 10, i % 91, i % 11); break;
      default: std::snprintf(line, sizeof line, "N%d G1 X%d Y0 A%d\n", i * 10, i % 83, i % 360); break;
    }
    prog += line;
  }
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  uint32_t f = sm.addBuffer("big.cnc", prog);
  Decoder dec(sm, f, diags);
  ElementQueue q(16);
  long allocs0 = gAllocs.load();
  size_t count = 0, maxSize = 0;
  for (;;) {
    StepResult r = dec.step(q, 50);
    maxSize = std::max(maxSize, q.size());
    while (!q.empty()) {
      ++count;
      q.pop();
    }
    if (r.status == StepStatus::Finished) break;
  }
  long allocs = gAllocs.load() - allocs0;
  EXPECT_EQ(dec.errorCount(), 0u);
  EXPECT_EQ(count, 10000u);
  EXPECT_LE(maxSize, 16u);
  // The block-number index is the only growth: 32 KiB slots for 10,000 N,
  // reached by doubling (no allocation per block).
  EXPECT_LE(dec.indexBytes(), 10000u * 64);
  EXPECT_LE(allocs, 24) << "heap allocations while decoding 10,000 blocks";
}

}  // namespace
}  // namespace stc::cnc::test

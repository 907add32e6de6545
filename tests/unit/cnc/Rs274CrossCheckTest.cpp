// Cross-check of the decoder against LinuxCNC's independent interpreter rs274:
// tests/cnc/rs274 holds programs in both spellings and rs274's canonical trace
// of each (tools/rs274_fixtures.py, format in tests/cnc/rs274/README.md).  Our
// decoder gets the DIN 66025 spelling; every TRAVERSE / LINE / ARC / DWELL /
// SETPOS record must match an element in order (end points and arc centres
// 1e-9, plane, direction, source line) and every FEED the velocity of the
// motion elements after it.  The 30 programs with tool radius compensation go
// through the decoder and then ToolCorr in TC_RAMP_IN, whose entry and exit are
// rs274's (docs/cnc.md, "Tool radius correction"): every record is compared the
// same way, corner arcs included.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "basic/Diagnostics.h"
#include "basic/SourceManager.h"
#include "stdlib-motion/cnc/Decoder.h"
#include "stdlib-motion/cnc/ToolCorr.h"

#ifndef STC_RS274_DIR
#error "STC_RS274_DIR (tests/cnc/rs274) must be defined"
#endif

namespace stc::cnc {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct Program {
  std::string name, flags;
};

std::vector<Program> corpus() {
  std::vector<Program> out;
  std::istringstream in(readFile(std::string(STC_RS274_DIR) + "/index.txt"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream l(line);
    Program p;
    std::string kind, elements, draws;
    l >> p.name >> kind >> elements >> draws >> p.flags;
    out.push_back(p);
  }
  return out;
}

bool has(const std::string& flags, const std::string& f) { return ("," + flags + ",").find("," + f + ",") != std::string::npos; }

constexpr double kTol = 1e-9;

// Checks one program; returns the number of records compared (failures via EXPECT).
int checkProgram(const Program& p, bool toolCorr) {
  SCOPED_TRACE(p.name);
  const std::string dir = STC_RS274_DIR;
  SourceManager sm;
  DiagnosticsEngine diags(sm);
  diags.opts.errorLimit = 0;
  const uint32_t file = sm.addBuffer(p.name + ".cnc", readFile(dir + "/din/" + p.name + ".cnc"));
  std::istringstream trace(readFile(dir + "/trace/" + p.name + ".txt"));
  std::string line;
  DecoderOptions opts;
  std::vector<std::string> records;
  while (std::getline(trace, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("START", 0) == 0) {
      std::istringstream l(line.substr(5));
      l >> opts.startPosition[AxX] >> opts.startPosition[AxY] >> opts.startPosition[AxZ];
      continue;
    }
    records.push_back(line);
  }
  std::vector<Element> els = decodeAll(sm, file, diags, opts);
  EXPECT_EQ(diags.errorCount(), 0u) << (diags.diagnostics().empty() ? "" : renderText(sm, diags.diagnostics()[0]));
  if (toolCorr) {
    ToolCorrError err = ToolCorrError::None;
    els = correctAll(els, ToolCorrMode::RampIn, 0, &err);
    EXPECT_EQ(err, ToolCorrError::None);
  }
  size_t next = 0;
  double feed = -1;
  int compared = 0;
  for (const std::string& r : records) {
    std::istringstream l(r);
    std::string kind;
    int src = 0;
    l >> kind >> src;
    SCOPED_TRACE(r);
    if (kind == "FEED") {
      double perMin = 0;
      l >> perMin >> feed;
      continue;
    }
    if (kind == "PLANE") continue;   // a modal state, checked through the arcs' planes
    if (kind == "COMP") continue;    // G41/G42/G40: what they do is in the records that follow
    // The next element of the decoder's output.
    if (next >= els.size()) {
      ADD_FAILURE() << "the decoder produced fewer elements than the trace";
      return compared;
    }
    const Element& e = els[next++];
    EXPECT_EQ(e.line, src);
    double x = 0, y = 0, z = 0;
    if (kind == "TRAVERSE" || kind == "LINE" || kind == "ARC" || kind == "SETPOS") l >> x >> y >> z;
    auto endIs = [&] {
      EXPECT_NEAR(e.end[AxX], x, kTol);
      EXPECT_NEAR(e.end[AxY], y, kTol);
      EXPECT_NEAR(e.end[AxZ], z, kTol);
    };
    if (kind == "TRAVERSE") {
      EXPECT_EQ(e.type, MoveType::LinPos);
      endIs();
    } else if (kind == "LINE") {
      EXPECT_EQ(e.type, MoveType::Lin);
      endIs();
      if (feed >= 0) {
        EXPECT_NEAR(e.vel, feed, 1e-12);
      }
    } else if (kind == "ARC") {
      double cx = 0, cy = 0, cz = 0;
      std::string plane;
      int rot = 0;
      l >> cx >> cy >> cz >> plane >> rot;
      EXPECT_EQ(e.type, rot < 0 ? MoveType::Clw : MoveType::Cclw);
      endIs();
      EXPECT_NEAR(e.arc.centre[0], cx, kTol);
      EXPECT_NEAR(e.arc.centre[1], cy, kTol);
      EXPECT_NEAR(e.arc.centre[2], cz, kTol);
      const Plane want = plane == "XY" ? Plane::XY : plane == "XZ" ? Plane::ZX : Plane::YZ;
      EXPECT_EQ(e.plane, want);
      if (feed >= 0) {
        EXPECT_NEAR(e.vel, feed, 1e-12);
      }
    } else if (kind == "DWELL") {
      double t = 0;
      l >> t;
      EXPECT_EQ(e.type, MoveType::Dwell);
      EXPECT_NEAR(e.dwell, t, 1e-12);
    } else if (kind == "SETPOS") {
      EXPECT_EQ(e.type, MoveType::InitPos);
      endIs();
    } else {
      ADD_FAILURE() << "unknown record";
    }
    ++compared;
  }
  EXPECT_EQ(next, els.size()) << "the decoder produced more elements than the trace";
  return compared;
}

TEST(Rs274CrossCheck, DecodedGeometryMatchesRs274) {
  const std::vector<Program> programs = corpus();
  ASSERT_GE(programs.size(), 100u);
  int checked = 0, records = 0;
  for (const Program& p : programs) {
    if (has(p.flags, "comp_left") || has(p.flags, "comp_right")) continue;   // below
    records += checkProgram(p, false);
    ++checked;
  }
  EXPECT_GE(checked, 80);
  RecordProperty("programs", checked);
  RecordProperty("records", records);
  std::printf("rs274 cross-check: %d programs, %d records\n", checked, records);
}

// The programs with G41/G42: decoder + ToolCorr (TC_RAMP_IN) against rs274's compensated path.
TEST(Rs274CrossCheck, ToolCorrMatchesRs274) {
  int checked = 0, records = 0;
  for (const Program& p : corpus()) {
    if (!has(p.flags, "comp_left") && !has(p.flags, "comp_right")) continue;
    records += checkProgram(p, true);
    ++checked;
  }
  EXPECT_EQ(checked, 30);
  RecordProperty("programs", checked);
  RecordProperty("records", records);
  std::printf("rs274 tool correction cross-check: %d programs, %d records\n", checked, records);
}

}  // namespace
}  // namespace stc::cnc

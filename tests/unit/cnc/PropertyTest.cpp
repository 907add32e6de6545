// Random valid programs (lines, arcs in the three planes by centre, radius
// and sweep, helices, splines, parabolas, offsets, G90/G91, G92, H, M, dwell,
// a counted loop): decoding never fails, the element count and every end
// point are what the generator expects, elements chain without gaps, and
// streaming in tiny steps gives the same elements.
#include <cmath>
#include <random>

#include "CncTestUtil.h"

namespace stc::cnc::test {
namespace {

struct Expect {
  MoveType type;
  Pos end;
};

class Gen {
public:
  explicit Gen(uint64_t seed) : rng_(seed) {}

  std::string program(int blocks) {
    text_ = "% random\n";
    for (int i = 0; i < blocks; ++i) block();
    return text_;
  }
  const std::vector<Expect>& expected() const { return exp_; }

private:
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  // A value written with three decimals, and the double the decoder reads.
  std::string q(double v, double& read) {
    long long k = std::llround(v * 1000);
    read = static_cast<double>(k < 0 ? -k : k) / 1000.0;
    if (k < 0) read = -read;
    std::string s = std::to_string(k < 0 ? -k : k);
    while (s.size() < 4) s = "0" + s;
    s.insert(s.size() - 3, ".");
    return (k < 0 ? "-" : "") + s;
  }
  void line(const std::string& s) {
    text_ += "N" + std::to_string(n_ += 10) + " " + s + "\n";
  }
  // Writes an axis word whose machine target is about `target`; returns the
  // machine value the decoder computes from the written text.
  double axis(char letter, int a, double target, std::string& words) {
    double v, m;
    if (inc_) {
      words += " " + std::string(1, letter) + q(target - pos_[a], v);
      m = pos_[a] + v;
    } else {
      words += " " + std::string(1, letter) + q(target - off_[a], v);
      m = v + off_[a];
    }
    return m;
  }

  void block() {
    int kind = integer(0, 15);
    switch (kind) {
      case 0: case 1: case 2: lineBlock(); break;
      case 3: case 4: arcByCentre(); break;
      case 5: arcByRadius(); break;
      case 6: arcBySweep(); break;
      case 7: spline(); break;
      case 8: parabola(); break;
      case 9: {   // M with parameters, or a dwell
        if (integer(0, 1)) {
          line("M" + std::to_string(integer(1, 65532)) + " K" + std::to_string(integer(-9, 9)) + " L2.5");
          exp_.push_back({MoveType::MCommand, pos_});
        } else {
          line("G4 T0." + std::to_string(integer(1, 9)));
          exp_.push_back({MoveType::Dwell, pos_});
        }
        break;
      }
      case 10: {   // offsets
        int which = integer(0, 2);
        if (which == 0) {
          line("G53");
          off_ = Pos{};
        } else {
          double v;
          std::string w = "G54 X" + q(real(-50, 50), v);
          Pos o{};
          o[AxX] = v;
          w += " Y" + q(real(-50, 50), v);
          o[AxY] = v;
          line(w);
          off_ = o;
        }
        break;
      }
      case 11:
        inc_ = !inc_;
        line(inc_ ? "G91" : "G90");
        break;
      case 12: {   // G92: program coordinates, always absolute
        double v;
        std::string w = "G92 X" + q(real(-100, 100), v);
        Pos p = pos_;
        p[AxX] = v + off_[AxX];
        line(w);
        pos_ = p;
        exp_.push_back({MoveType::InitPos, pos_});
        break;
      }
      case 13: {   // plane
        int p = integer(17, 19);
        plane_ = p;
        line("G" + std::to_string(p));
        break;
      }
      case 14: {   // a counted loop of two relative lines
        int times = integer(1, 4);
        int start = n_ + 20;
        line("G36 D" + std::to_string(times));
        line("G91 G1 X1 F50");
        line("G1 Y-1");
        line("G37 D-1");
        line("G20 L" + std::to_string(start));
        line(inc_ ? "G91" : "G90");
        for (int i = 0; i < times; ++i) {
          pos_[AxX] += 1;
          exp_.push_back({MoveType::Lin, pos_});
          pos_[AxY] += -1;
          exp_.push_back({MoveType::Lin, pos_});
        }
        break;
      }
      default:
        lineBlock();
        break;
    }
  }

  void lineBlock() {
    std::string w = integer(0, 3) == 0 ? "G0" : "G1";
    Pos t = pos_;
    // X always changes so that the block moves.
    double x = pos_[AxX] + (integer(0, 1) ? 1 : -1) * real(1, 40);
    t[AxX] = axis('X', AxX, x, w);
    if (integer(0, 1)) t[AxY] = axis('Y', AxY, real(-100, 100), w);
    if (integer(0, 3) == 0) t[AxZ] = axis('Z', AxZ, real(-20, 20), w);
    if (integer(0, 4) == 0) t[AxA] = axis('A', AxA, real(-180, 180), w);
    if (integer(0, 4) == 0) t[AxP] = axis('P', AxP, real(0, 10), w);
    if (w == "G1" && integer(0, 2) == 0) w += " H" + std::to_string(integer(1, 30)) + " L0.5 H-2 O0.75";
    if (integer(0, 3) == 0) w += " F" + std::to_string(integer(1, 500));
    line(w);
    pos_ = t;
    exp_.push_back({w[1] == '0' ? MoveType::Lin : MoveType::Lin, pos_});
    if (w[1] == '0') exp_.back().type = MoveType::LinPos;
  }

  // In-plane axes of the active plane: (u, v, normal) as axis indices and
  // the centre letters of u and v.
  void planeAxes(int& u, int& v, int& n, char& lu, char& lv, char& cu, char& cv) const {
    if (plane_ == 18) { u = AxZ; v = AxX; n = AxY; lu = 'Z'; lv = 'X'; cu = 'K'; cv = 'I'; }
    else if (plane_ == 19) { u = AxY; v = AxZ; n = AxX; lu = 'Y'; lv = 'Z'; cu = 'J'; cv = 'K'; }
    else { u = AxX; v = AxY; n = AxZ; lu = 'X'; lv = 'Y'; cu = 'I'; cv = 'J'; }
  }

  void arcByCentre() {
    int u, v, n;
    char lu, lv, cu, cv;
    planeAxes(u, v, n, lu, lv, cu, cv);
    bool cw = integer(0, 1);
    std::string w = cw ? "G2" : "G3";
    double du, dv;
    double r = real(2, 30), a0 = real(0, 6.28);
    std::string cs = " " + std::string(1, cu) + q(-r * std::cos(a0), du) + " " + std::string(1, cv) + q(-r * std::sin(a0), dv);
    double cU = pos_[u] + du, cV = pos_[v] + dv, rr = std::hypot(du, dv);
    double a1 = a0 + (cw ? -1 : 1) * real(0.3, 5.5);
    Pos t = pos_;
    t[u] = axis(lu, u, cU + rr * std::cos(a1), w);
    t[v] = axis(lv, v, cV + rr * std::sin(a1), w);
    if (integer(0, 2) == 0) t[n] = axis("XYZ"[n], n, pos_[n] + real(-5, 5), w);
    line(w + cs);
    pos_ = t;
    exp_.push_back({cw ? MoveType::Clw : MoveType::Cclw, pos_});
  }

  void arcByRadius() {
    int u, v, n;
    char lu, lv, cu, cv;
    planeAxes(u, v, n, lu, lv, cu, cv);
    bool cw = integer(0, 1);
    std::string w = cw ? "G2" : "G3";
    Pos t = pos_;
    t[u] = axis(lu, u, pos_[u] + real(3, 20) * (integer(0, 1) ? 1 : -1), w);
    t[v] = axis(lv, v, pos_[v] + real(-20, 20), w);
    double chord = std::hypot(t[u] - pos_[u], t[v] - pos_[v]);
    double rr;
    w += " R" + std::string(integer(0, 1) ? "-" : "") + q(chord * real(0.6, 3), rr);
    line(w);
    pos_ = t;
    exp_.push_back({cw ? MoveType::Clw : MoveType::Cclw, pos_});
  }

  void arcBySweep() {
    if (plane_ != 17) return arcByCentre();
    bool cw = integer(0, 1);
    double du, dv, tdeg;
    std::string w = std::string(cw ? "G2" : "G3") + " I" + q(real(-20, 20), du) + " J" + q(real(-20, 20), dv);
    if (std::hypot(du, dv) < 1) return arcByCentre();
    w += " T" + q(real(10, 700), tdeg);
    line(w);
    // The end follows from the sweep: compute it as the decoder does.
    double cx = pos_[AxX] + du, cy = pos_[AxY] + dv;
    double r = std::hypot(pos_[AxX] - cx, pos_[AxY] - cy);
    double a0 = std::atan2(pos_[AxY] - cy, pos_[AxX] - cx);
    double a1 = a0 + (cw ? -1 : 1) * tdeg * kPi / 180;
    pos_[AxX] = cx + r * std::cos(a1);
    pos_[AxY] = cy + r * std::sin(a1);
    exp_.push_back({cw ? MoveType::Clw : MoveType::Cclw, pos_});
    approx_ = true;
  }

  void spline() {
    bool threeD = integer(0, 1);
    if (!threeD && plane_ != 17) {
      plane_ = 17;
      line("G17");
    }
    std::string w = threeD ? "G10" : "G5";
    Pos t = pos_;
    t[AxX] = axis('X', AxX, pos_[AxX] + real(2, 20), w);
    t[AxY] = axis('Y', AxY, pos_[AxY] + real(-20, 20), w);
    if (threeD) t[AxZ] = axis('Z', AxZ, real(-10, 10), w);
    line(w);
    pos_ = t;
    exp_.push_back({MoveType::Spline, pos_});
  }

  void parabola() {
    if (plane_ != 17) {
      plane_ = 17;
      line("G17");
    }
    std::string w = "G6";
    Pos t = pos_;
    t[AxX] = axis('X', AxX, pos_[AxX] + real(5, 30), w);
    t[AxY] = axis('Y', AxY, pos_[AxY] + real(-30, 30), w);
    double vi, vj;
    w += " I" + q(real(1, 4), vi) + " J" + q(real(-10, 10), vj);
    line(w);
    pos_ = t;
    exp_.push_back({MoveType::Parabola, pos_});
  }

  std::mt19937_64 rng_;
  std::string text_;
  std::vector<Expect> exp_;
  Pos pos_{}, off_{};
  bool inc_ = false;
  int plane_ = 17;
  int n_ = 0;

public:
  bool approx_ = false;   // sweep arcs: end points computed, compare to 1e-9
};

TEST(CncProperty, RandomValidProgramsDecodeAsExpected) {
  int programs = 0;
  size_t elements = 0;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    Gen g(seed);
    std::string prog = g.program(60);
    Decoded r(prog);
    ASSERT_EQ(r.errors(), 0u) << "seed " << seed << "\n" << r.all() << prog;
    const auto& ex = g.expected();
    ASSERT_EQ(r.els.size(), ex.size()) << "seed " << seed << "\n" << prog;
    for (size_t i = 0; i < ex.size(); ++i) {
      const Element& e = r.els[i];
      ASSERT_EQ(e.type, ex[i].type) << "seed " << seed << " element " << i;
      for (int a = 0; a < kAxisCount; ++a)
        ASSERT_NEAR(e.end[a], ex[i].end[a], 1e-9 * std::max(1.0, std::fabs(ex[i].end[a])))
            << "seed " << seed << " element " << i << " axis " << axisLetter(static_cast<Axis>(a)) << "\n" << prog;
      // Elements chain without gaps; u = 0 / 1 are the exact end points.
      if (i > 0) {
        ASSERT_EQ(e.start, r.els[i - 1].end) << "seed " << seed << " element " << i;
      }
      ASSERT_EQ(e.objNo, static_cast<int>(i + 1));
      ASSERT_EQ(point(e, 0), e.start);
      ASSERT_EQ(point(e, 1), e.end);
      if (isMotion(e.type)) {
        ASSERT_GE(e.length, norm(xyz(e.end) - xyz(e.start)) - 1e-9) << "seed " << seed << " element " << i;
        ASSERT_TRUE(std::isfinite(e.length));
      }
      if (e.type == MoveType::Clw || e.type == MoveType::Cclw) {
        Vec3 s = xyz(e.start) - e.arc.centre;
        Vec3 t = xyz(e.end) - e.arc.centre - e.arc.rise * e.arc.normal;
        EXPECT_NEAR(norm(s), e.arc.radius, 1e-9 * e.arc.radius);
        EXPECT_NEAR(norm(t), e.arc.radius, 1e-9 * e.arc.radius);
        EXPECT_NEAR(dot(s, e.arc.normal), 0, 1e-9);
        EXPECT_LE(std::fabs(e.arc.sweep), 2 * kPi * 2 + 1e-9);
        // The polyline through the arc is shorter than its length.
        double poly = 0;
        for (int k = 1; k <= 64; ++k) poly += norm(xyz(point(e, k / 64.0)) - xyz(point(e, (k - 1) / 64.0)));
        EXPECT_LE(poly, e.length + 1e-9);
        EXPECT_GE(poly, e.length * 0.98);
      }
    }
    // Streaming in steps of one block into the smallest queue.
    SourceManager sm;
    DiagnosticsEngine diags(sm);
    Decoder dec(sm, sm.addBuffer("p.cnc", prog), diags);
    ElementQueue q(ElementQueue::kMinCapacity);
    size_t k = 0;
    for (;;) {
      StepResult s = dec.step(q, 1);
      while (!q.empty()) {
        ASSERT_LT(k, r.els.size());
        ASSERT_EQ(q.front().end, r.els[k].end);
        ASSERT_EQ(q.front().type, r.els[k].type);
        ++k;
        q.pop();
      }
      if (s.status == StepStatus::Finished) break;
    }
    ASSERT_EQ(k, r.els.size());
    ++programs;
    elements += r.els.size();
  }
  EXPECT_EQ(programs, 300);
  EXPECT_GT(elements, 10000u);
}

}  // namespace
}  // namespace stc::cnc::test

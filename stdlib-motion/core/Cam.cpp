// Cam tables, motion laws, tappets and the .CAM text format (Cam.h,
// docs/motion-cam.md).
#include "stdlib-motion/core/Cam.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>

#include "stdlib-motion/core/InputBounds.h"

namespace stc::motion {

namespace {

bool plausible(double v) { return bounds::position(v); }

// The quintic on [0, h] (local t) with value, slope and curvature given at both ends.
void quintic(const CamXYVA& p0, const CamXYVA& p1, double c[6]) {
  const double h = p1.x - p0.x, H = p1.y - p0.y;
  const double d0 = p0.v * h, d1 = p1.v * h, e0 = p0.a * h * h, e1 = p1.a * h * h;
  const double b[6] = {p0.y,
                       d0,
                       0.5 * e0,
                       10 * H - 6 * d0 - 4 * d1 - 1.5 * e0 + 0.5 * e1,
                       -15 * H + 8 * d0 + 7 * d1 + 1.5 * e0 - e1,
                       6 * H - 3 * d0 - 3 * d1 - 0.5 * e0 + 0.5 * e1};
  double hk = 1;
  for (int k = 0; k < 6; ++k, hk *= h) c[k] = b[k] / hk;
}

bool validTappets(const std::vector<Tappet>& ts, double x0, double x1, std::string& error) {
  if (ts.size() > static_cast<size_t>(kMaxCamElements)) return error = "too many tappets", false;
  for (const Tappet& t : ts) {
    if (!std::isfinite(t.x) || t.x < x0 || t.x > x1) return error = "a tappet lies outside the cam's master range", false;
    if (t.group < 1 || t.group > kMaxTappetGroups) return error = "a tappet group id is outside 1..512", false;
    if (static_cast<int>(t.positive) > 3 || static_cast<int>(t.negative) > 3) return error = "a tappet action is not none/on/off/invert", false;
  }
  return true;
}

}  // namespace

bool Cam::finish(std::vector<Tappet> tappets, std::string& error) {
  if (!validTappets(tappets, x0_, x1_, error)) return false;
  std::stable_sort(tappets.begin(), tappets.end(), [](const Tappet& a, const Tappet& b) { return a.x < b.x; });
  tappets_ = std::move(tappets);
  yStart_ = at(x0_).y;
  yEnd_ = at(x1_).y;
  // Extremes: the nodes, then 64 samples inside each non-linear segment.
  CamExtremes e{yStart_, yStart_, at(x0_).dy, at(x0_).dy, at(x0_).ddy, at(x0_).ddy};
  auto take = [&](const CamSample& s) {
    e.yMin = std::min(e.yMin, s.y), e.yMax = std::max(e.yMax, s.y);
    e.dyMin = std::min(e.dyMin, s.dy), e.dyMax = std::max(e.dyMax, s.dy);
    e.ddyMin = std::min(e.ddyMin, s.ddy), e.ddyMax = std::max(e.ddyMax, s.ddy);
  };
  for (size_t i = 0; i < seg_.size(); ++i) {
    const double a = xs_[i], b = i + 1 < xs_.size() ? xs_[i + 1] : x1_;
    const int n = kind_ == CamKind::XYVA ? 64 : 1;
    for (int k = 0; k <= n; ++k) {
      const double t = (b - a) * k / n;
      const double* c = seg_[i].c;
      take(CamSample{c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5])))),
                     c[1] + t * (2 * c[2] + t * (3 * c[3] + t * (4 * c[4] + t * 5 * c[5]))),
                     2 * c[2] + t * (6 * c[3] + t * (12 * c[4] + t * 20 * c[5]))});
    }
  }
  ext_ = e;
  return true;
}

bool Cam::xyva(std::vector<CamXYVA> pts, std::vector<Tappet> tappets, Cam& out, std::string& error) {
  if (pts.size() < 2) return error = "an XYVA cam needs at least 2 points", false;
  if (pts.size() > static_cast<size_t>(kMaxCamElements)) return error = "too many points", false;
  for (size_t i = 0; i < pts.size(); ++i) {
    const CamXYVA& p = pts[i];
    if (!plausible(p.x) || !plausible(p.y) || !plausible(p.v) || !plausible(p.a)) return error = "a point is not finite or absurdly large", false;
    if (i > 0 && !(p.x > pts[i - 1].x)) return error = "the master positions must increase", false;
  }
  Cam c;
  c.kind_ = CamKind::XYVA;
  c.x0_ = pts.front().x;
  c.x1_ = pts.back().x;
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    c.xs_.push_back(pts[i].x);
    Poly p;
    quintic(pts[i], pts[i + 1], p.c);
    c.seg_.push_back(p);
  }
  c.pts_ = std::move(pts);
  if (!c.finish(std::move(tappets), error)) return false;
  out = std::move(c);
  return true;
}

bool Cam::table1D(double xStart, double xEnd, std::vector<double> ys, std::vector<Tappet> tappets, Cam& out, std::string& error) {
  if (ys.size() < 2) return error = "a 1-D cam table needs at least 2 values", false;
  if (ys.size() > static_cast<size_t>(kMaxCamElements)) return error = "too many values", false;
  if (!plausible(xStart) || !plausible(xEnd) || !(xEnd > xStart)) return error = "the master range must be finite with xEnd > xStart", false;
  for (double y : ys)
    if (!plausible(y)) return error = "a value is not finite or absurdly large", false;
  Cam c;
  c.kind_ = CamKind::Table1D;
  c.x0_ = xStart;
  c.x1_ = xEnd;
  c.step_ = (xEnd - xStart) / static_cast<double>(ys.size() - 1);
  for (size_t i = 0; i + 1 < ys.size(); ++i) {
    c.xs_.push_back(xStart + c.step_ * static_cast<double>(i));
    Poly p;
    p.c[0] = ys[i];
    p.c[1] = (ys[i + 1] - ys[i]) / c.step_;
    c.seg_.push_back(p);
    c.pts_.push_back(CamXYVA{c.xs_.back(), ys[i], 0, 0});
  }
  c.pts_.push_back(CamXYVA{xEnd, ys.back(), 0, 0});
  c.ys_ = std::move(ys);
  if (!c.finish(std::move(tappets), error)) return false;
  out = std::move(c);
  return true;
}

bool Cam::table2D(std::vector<std::array<double, 2>> pts, std::vector<Tappet> tappets, Cam& out, std::string& error) {
  if (pts.size() < 2) return error = "a 2-D cam table needs at least 2 points", false;
  if (pts.size() > static_cast<size_t>(kMaxCamElements)) return error = "too many points", false;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!plausible(pts[i][0]) || !plausible(pts[i][1])) return error = "a point is not finite or absurdly large", false;
    if (i > 0 && !(pts[i][0] > pts[i - 1][0])) return error = "the master positions must increase", false;
  }
  Cam c;
  c.kind_ = CamKind::Table2D;
  c.x0_ = pts.front()[0];
  c.x1_ = pts.back()[0];
  for (size_t i = 0; i < pts.size(); ++i) {
    c.pts_.push_back(CamXYVA{pts[i][0], pts[i][1], 0, 0});
    if (i + 1 == pts.size()) break;
    c.xs_.push_back(pts[i][0]);
    Poly p;
    p.c[0] = pts[i][1];
    p.c[1] = (pts[i + 1][1] - pts[i][1]) / (pts[i + 1][0] - pts[i][0]);
    c.seg_.push_back(p);
  }
  if (!c.finish(std::move(tappets), error)) return false;
  out = std::move(c);
  return true;
}

size_t Cam::segmentOf(double x) const {
  if (kind_ == CamKind::Table1D) {
    const double k = std::floor((x - x0_) / step_);
    return k <= 0 ? 0 : std::min(static_cast<size_t>(k), seg_.size() - 1);
  }
  // The last segment start <= x (binary search).
  auto it = std::upper_bound(xs_.begin(), xs_.end(), x);
  return it == xs_.begin() ? 0 : static_cast<size_t>(it - xs_.begin()) - 1;
}

CamSample Cam::at(double x) const {
  if (seg_.empty()) return {};
  x = std::clamp(x, x0_, x1_);
  const size_t i = segmentOf(x);
  const double t = x - xs_[i];
  const double* c = seg_[i].c;
  return CamSample{c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5])))),
                   c[1] + t * (2 * c[2] + t * (3 * c[3] + t * (4 * c[4] + t * 5 * c[5]))),
                   2 * c[2] + t * (6 * c[3] + t * (12 * c[4] + t * 20 * c[5]))};
}

// ---- Motion laws ------------------------------------------------------------

namespace {

// One piece of a law's acceleration over [u0, u1]: A·sin(w·t + phi), t = u - u0 (w = 0: constant A).
struct LawPiece {
  double u0, u1, A, w, phi;
};

// Integrates the pieces from rest up to u (unnormalised).
CamSample integrate(const LawPiece* pieces, int n, double u) {
  double s = 0, v = 0;
  for (int i = 0; i < n; ++i) {
    const LawPiece& p = pieces[i];
    const double t = std::min(u, p.u1) - p.u0;
    double a, vt, st;
    if (p.w == 0) {
      a = p.A;
      vt = v + p.A * t;
      st = s + v * t + 0.5 * p.A * t * t;
    } else {
      a = p.A * std::sin(p.w * t + p.phi);
      vt = v + p.A / p.w * (std::cos(p.phi) - std::cos(p.w * t + p.phi));
      st = s + v * t + p.A / p.w * (t * std::cos(p.phi) - (std::sin(p.w * t + p.phi) - std::sin(p.phi)) / p.w);
    }
    if (u <= p.u1 || i == n - 1) return CamSample{st, vt, a};
    s = st;
    v = vt;
  }
  return {};
}

CamSample normalised(const LawPiece* pieces, int n, double u) {
  const double scale = integrate(pieces, n, 1.0).y;   // the rise with unit amplitude
  CamSample r = integrate(pieces, n, u);
  return CamSample{r.y / scale, r.dy / scale, r.ddy / scale};
}

constexpr double kPi = std::numbers::pi;

}  // namespace

CamSample motionLaw(MotionLaw law, double u) {
  u = std::clamp(u, 0.0, 1.0);
  switch (law) {
  case MotionLaw::Linear:
    return CamSample{u, 1, 0};
  case MotionLaw::Poly345:
    return CamSample{u * u * u * (10 + u * (-15 + 6 * u)), u * u * (30 + u * (-60 + 30 * u)), u * (60 + u * (-180 + 120 * u))};
  case MotionLaw::Harmonic: {
    static const LawPiece p[] = {{0, 1, 1, kPi, kPi / 2}};
    return normalised(p, 1, u);
  }
  case MotionLaw::Cycloid: {
    static const LawPiece p[] = {{0, 1, 1, 2 * kPi, 0}};
    return normalised(p, 1, u);
  }
  case MotionLaw::ModifiedSine: {
    static const LawPiece p[] = {{0, 0.125, 1, 4 * kPi, 0}, {0.125, 0.875, 1, 4 * kPi / 3, kPi / 2}, {0.875, 1, 1, 4 * kPi, -kPi / 2}};
    return normalised(p, 3, u);
  }
  case MotionLaw::ModifiedTrapezoid: {
    static const LawPiece p[] = {{0, 0.125, 1, 4 * kPi, 0},
                                 {0.125, 0.375, 1, 0, 0},
                                 {0.375, 0.625, 1, 4 * kPi, kPi / 2},
                                 {0.625, 0.875, -1, 0, 0},
                                 {0.875, 1, 1, 4 * kPi, -kPi / 2}};
    return normalised(p, 5, u);
  }
  }
  return {};
}

bool motionLawNamed(const std::string& name, MotionLaw& out) {
  static const std::pair<const char*, MotionLaw> names[] = {
      {"linear", MotionLaw::Linear},          {"harmonic", MotionLaw::Harmonic},
      {"cycloid", MotionLaw::Cycloid},        {"modified_sine", MotionLaw::ModifiedSine},
      {"modified_trapezoid", MotionLaw::ModifiedTrapezoid}, {"poly345", MotionLaw::Poly345}};
  for (const auto& [n, l] : names)
    if (name == n) return out = l, true;
  return false;
}

void appendMotionLaw(MotionLaw law, double x0, double x1, double y0, double y1, std::vector<CamXYVA>& pts, double baseSlope) {
  const double L = x1 - x0, H = y1 - y0;
  const bool exact = law == MotionLaw::Linear || law == MotionLaw::Poly345;
  const int n = exact ? 1 : 32;
  // y = y0 + b·(x - x0) + (H - b·L)·s(u): the law rises on top of the base slope b.
  const double b = law == MotionLaw::Linear ? 0 : baseSlope, R = H - b * L;
  for (int k = pts.empty() ? 0 : 1; k <= n; ++k) {
    const double u = static_cast<double>(k) / n;
    const CamSample s = motionLaw(law, u);
    pts.push_back(CamXYVA{k == n ? x1 : x0 + L * u, k == n ? y1 : y0 + b * L * u + R * s.y, b + R / L * s.dy, R / (L * L) * s.ddy});
  }
}

// ---- Tappets ----------------------------------------------------------------

namespace {
constexpr uint8_t kArmPos = 1, kArmNeg = 2;
}

void TappetTracker::reset(const std::vector<Tappet>& tappets, double x, double hysteresis) {
  tappets_ = &tappets;
  h_ = hysteresis;
  groups_.fill(0);
  wrap(x);
}

void TappetTracker::wrap(double x) {
  const auto& ts = *tappets_;
  armed_.assign(ts.size(), 0);
  for (size_t i = 0; i < ts.size(); ++i) armed_[i] = (x < ts[i].x ? kArmPos : 0) | (x > ts[i].x ? kArmNeg : 0);
  last_ = x;
}

void TappetTracker::fire(const Tappet& t, TappetAction a) {
  uint8_t& g = groups_[static_cast<size_t>(t.group)];
  switch (a) {
  case TappetAction::None: return;
  case TappetAction::On: g = 8 | 1; break;
  case TappetAction::Off: g = 8 | 2; break;
  case TappetAction::Invert: g = static_cast<uint8_t>((g ^ 4) | 8); break;
  }
}

bool TappetTracker::move(double x) {
  const auto& ts = *tappets_;
  if (ts.empty() || x == last_) return (last_ = x), false;
  const double a = last_, b = x, lo = std::min(a, b) - h_, hi = std::max(a, b) + h_;
  bool fired = false;
  // The tappets near the path, in the order they are passed.
  const size_t first = static_cast<size_t>(std::lower_bound(ts.begin(), ts.end(), lo, [](const Tappet& t, double v) { return t.x < v; }) - ts.begin());
  size_t last = first;
  while (last < ts.size() && ts[last].x <= hi) ++last;
  auto visit = [&](size_t i) {
    const Tappet& t = ts[i];
    uint8_t& arm = armed_[i];
    if (b > a && a < t.x && t.x <= b && (arm & kArmPos)) {
      fire(t, t.positive);
      arm &= static_cast<uint8_t>(~kArmPos);
      fired |= t.positive != TappetAction::None;
    } else if (b < a && b < t.x && t.x <= a && (arm & kArmNeg)) {
      fire(t, t.negative);
      arm &= static_cast<uint8_t>(~kArmNeg);
      fired |= t.negative != TappetAction::None;
    }
    if (b >= t.x + h_ && b > t.x) arm |= kArmNeg;
    if (b <= t.x - h_ && b < t.x) arm |= kArmPos;
  };
  if (b > a)
    for (size_t i = first; i < last; ++i) visit(i);
  else
    for (size_t i = last; i-- > first;) visit(i);
  last_ = x;
  return fired;
}

// ---- The .CAM text format ---------------------------------------------------

const char* tappetActionName(TappetAction a) {
  switch (a) {
  case TappetAction::On: return "on";
  case TappetAction::Off: return "off";
  case TappetAction::Invert: return "invert";
  default: return "none";
  }
}

bool tappetActionNamed(const std::string& s, TappetAction& out) {
  for (TappetAction a : {TappetAction::None, TappetAction::On, TappetAction::Off, TappetAction::Invert})
    if (s == tappetActionName(a)) return out = a, true;
  return false;
}

namespace {

std::string num(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);   // shortest round-trip form
  return std::string(buf, r.ptr);
}

bool parseNum(const std::string& s, double& out) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(out);
}

}  // namespace

std::string writeCamText(const Cam& cam, const std::string& name) {
  std::ostringstream o;
  o << "STC-CAM 1\n";
  if (!name.empty()) o << "name " << name << "\n";
  switch (cam.kind()) {
  case CamKind::XYVA:
    o << "type xyva\npoints " << cam.points().size() << "\n";
    for (const CamXYVA& p : cam.points()) o << num(p.x) << " " << num(p.y) << " " << num(p.v) << " " << num(p.a) << "\n";
    break;
  case CamKind::Table1D:
    o << "type table1d\nmaster " << num(cam.xStart()) << " " << num(cam.xEnd()) << "\npoints " << cam.values().size() << "\n";
    for (double y : cam.values()) o << num(y) << "\n";
    break;
  case CamKind::Table2D:
    o << "type table2d\npoints " << cam.points().size() << "\n";
    for (const CamXYVA& p : cam.points()) o << num(p.x) << " " << num(p.y) << "\n";
    break;
  }
  o << "tappets " << cam.tappets().size() << "\n";
  for (const Tappet& t : cam.tappets()) o << num(t.x) << " " << t.group << " " << tappetActionName(t.positive) << " " << tappetActionName(t.negative) << "\n";
  o << "end\n";
  return o.str();
}

CamFileError readCamText(const std::string& text, Cam& out, std::string& name, std::string& detail) {
  std::istringstream in(text);
  std::string line;
  int lineNo = 0;
  // The next line that is not empty or a comment, split into words.
  auto next = [&](std::vector<std::string>& words) {
    while (std::getline(in, line)) {
      ++lineNo;
      words.clear();
      std::istringstream ls(line);
      for (std::string w; ls >> w;) {
        if (w[0] == '#') break;
        words.push_back(w);
      }
      if (!words.empty()) return true;
    }
    return false;
  };
  auto bad = [&](const std::string& what) {
    detail = "line " + std::to_string(lineNo) + ": " + what;
    return CamFileError::UnexpectedEnd;
  };
  std::vector<std::string> w;
  if (!next(w) || w.size() != 2 || w[0] != "STC-CAM") return detail = "not a .CAM file (no 'STC-CAM 1' header)", CamFileError::WrongType;
  if (w[1] != "1") return detail = "version " + w[1] + " (this stc reads version 1)", CamFileError::WrongVersion;
  std::string type;
  double xStart = 0, xEnd = 0;
  bool haveMaster = false;
  name.clear();
  for (;;) {
    if (!next(w)) return bad("the file ends before 'points'");
    if (w[0] == "name" && w.size() == 2) name = w[1];
    else if (w[0] == "type" && w.size() == 2) type = w[1];
    else if (w[0] == "master" && w.size() == 3) {
      if (!parseNum(w[1], xStart) || !parseNum(w[2], xEnd)) return bad("'master' needs two numbers");
      haveMaster = true;
    } else if (w[0] == "points") break;
    else return bad("unexpected '" + w[0] + "'");
  }
  const size_t cols = type == "xyva" ? 4 : type == "table2d" ? 2 : type == "table1d" ? 1 : 0;
  if (cols == 0) return detail = "unknown cam type '" + type + "' (xyva, table1d, table2d)", CamFileError::WrongType;
  double nd = 0;
  if (w.size() != 2 || !parseNum(w[1], nd) || nd < 0 || nd != std::floor(nd)) return bad("'points' needs a count");
  if (nd > kMaxCamElements) return detail = "more than 65536 points", CamFileError::TooMuchData;
  const size_t n = static_cast<size_t>(nd);
  std::vector<std::array<double, 4>> rows(n);
  for (size_t i = 0; i < n; ++i) {
    if (!next(w)) return bad("the file ends inside the points");
    if (w.size() != cols) return bad("a point needs " + std::to_string(cols) + " numbers");
    for (size_t k = 0; k < cols; ++k)
      if (!parseNum(w[k], rows[i][k])) return bad("'" + w[k] + "' is not a finite number");
  }
  std::vector<Tappet> tappets;
  if (!next(w)) return bad("the file ends before 'tappets'");
  double td = 0;
  if (w[0] != "tappets" || w.size() != 2 || !parseNum(w[1], td) || td < 0 || td != std::floor(td)) return bad("expected 'tappets <count>'");
  if (td > kMaxCamElements) return detail = "more than 65536 tappets", CamFileError::TooMuchData;
  for (size_t i = 0; i < static_cast<size_t>(td); ++i) {
    Tappet t;
    double g = 0;
    if (!next(w)) return bad("the file ends inside the tappets");
    if (w.size() != 4 || !parseNum(w[0], t.x) || !parseNum(w[1], g) || g != std::floor(g) || std::fabs(g) > 1e6 ||
        !tappetActionNamed(w[2], t.positive) || !tappetActionNamed(w[3], t.negative))
      return bad("a tappet is 'x group on|off|invert|none on|off|invert|none'");
    t.group = static_cast<int>(g);
    tappets.push_back(t);
  }
  if (!next(w) || w[0] != "end") return bad("missing 'end'");
  std::string err;
  bool ok;
  if (cols == 4) {
    std::vector<CamXYVA> pts;
    for (const auto& r : rows) pts.push_back(CamXYVA{r[0], r[1], r[2], r[3]});
    ok = Cam::xyva(std::move(pts), std::move(tappets), out, err);
  } else if (cols == 2) {
    std::vector<std::array<double, 2>> pts;
    for (const auto& r : rows) pts.push_back({r[0], r[1]});
    ok = Cam::table2D(std::move(pts), std::move(tappets), out, err);
  } else {
    if (!haveMaster) return bad("a table1d cam needs 'master <xStart> <xEnd>'");
    std::vector<double> ys;
    for (const auto& r : rows) ys.push_back(r[0]);
    ok = Cam::table1D(xStart, xEnd, std::move(ys), std::move(tappets), out, err);
  }
  if (!ok) return detail = err, CamFileError::UnexpectedEnd;
  return CamFileError::None;
}

}  // namespace stc::motion

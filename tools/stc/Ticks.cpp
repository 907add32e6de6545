#include "tools/stc/Ticks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

namespace stc::plot {
namespace {

// Data beyond this magnitude is drawn at it (the spans below stay finite).
constexpr double kLimit = 1e300;

// The k-th multiple of step, with an exact zero.
double multiple(double k, double step) {
  double v = k * step;
  return std::fabs(v) < step * 1e-9 ? 0.0 : v;
}

// How many multiples of step lie in [lo, hi] (within rounding).
double tickCount(double lo, double hi, double step) {
  return std::floor(hi / step + 1e-9) - std::ceil(lo / step - 1e-9) + 1;
}

// "2.0e+08" -> "2.0e8", "1.5e-07" -> "1.5e-7".
std::string shortExponent(std::string s) {
  size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mant = s.substr(0, e), ex = s.substr(e + 1);
  bool neg = !ex.empty() && ex[0] == '-';
  if (!ex.empty() && (ex[0] == '+' || ex[0] == '-')) ex.erase(0, 1);
  ex.erase(0, std::min(ex.find_first_not_of('0'), ex.size() - 1));
  return mant + "e" + (neg ? "-" : "") + ex;
}

// 1.50e9 -> 1.5e9, 1.0e9 -> 1e9 (labels stay distinct: their values differ).
std::string trimMantissa(const std::string& s) {
  const size_t e = s.find('e');
  std::string mant = s.substr(0, e);
  if (mant.find('.') != std::string::npos) {
    while (!mant.empty() && mant.back() == '0') mant.pop_back();
    if (!mant.empty() && mant.back() == '.') mant.pop_back();
  }
  return e == std::string::npos ? mant : mant + s.substr(e);
}

std::vector<std::string> labelsWith(const std::vector<double>& ticks, bool fixed, int digits) {
  std::vector<std::string> out;
  for (double v : ticks) {
    std::string s = v == 0 ? "0" : fixed ? fmt::format("{:.{}f}", v, digits) : shortExponent(fmt::format("{:.{}e}", v, digits));
    if (!fixed) s = trimMantissa(s);
    if (s.find_first_not_of("-0.") == std::string::npos) s = "0";   // "-0.00"
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

double textWidth(const std::string& s, double perChar) {
  size_t n = 0;
  for (unsigned char c : s)
    if ((c & 0xC0) != 0x80) ++n;
  return static_cast<double>(n) * perChar;
}

std::vector<double> tickValues(double lo, double hi, double step) {
  std::vector<double> out;
  if (!(step > 0) || !std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi)) return out;
  const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last && out.size() < 200; k += 1) out.push_back(multiple(k, step));
  return out;
}

std::vector<std::string> tickLabels(const std::vector<double>& ticks, double step) {
  if (ticks.empty() || !(step > 0)) return labelsWith(ticks, true, 0);
  double maxAbs = 0;
  for (double v : ticks) maxAbs = std::max(maxAbs, std::fabs(v));
  // Decimals that write the step exactly (0.25: 2), in fixed notation.
  int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step))));
  while (decimals < 20) {
    double scaled = step * std::pow(10.0, decimals);
    if (std::fabs(scaled - std::round(scaled)) <= 1e-6 * scaled) break;
    ++decimals;
  }
  const bool fixed = maxAbs < 1e7 && maxAbs >= 1e-4 && decimals <= 9;
  int digits = decimals;
  if (!fixed) {
    // Exponent notation: the digits from the largest tick's first down to the
    // step's last (2.5e-8 has two).
    const double e = std::floor(std::log10(step));
    const double mantissa = step / std::pow(10.0, e);
    int extra = 0;
    while (extra < 3 && std::fabs(mantissa * std::pow(10.0, extra) - std::round(mantissa * std::pow(10.0, extra))) > 1e-6) ++extra;
    digits = std::max(0, static_cast<int>(std::floor(std::log10(std::max(maxAbs, step))) - e)) + extra;
  }
  for (;; ++digits) {
    std::vector<std::string> labels = labelsWith(ticks, fixed, digits);
    if (std::set<std::string>(labels.begin(), labels.end()).size() == labels.size() || digits >= 17) return labels;
  }
}

double chooseStep(double lo, double hi, const TickRequest& r) {
  const double span = hi - lo;
  if (!(span > 0) || !std::isfinite(span)) return 1;
  const double target = std::clamp(std::round(r.pixels / (r.horizontal ? 90.0 : 40.0)), 3.0, 10.0);
  struct Candidate {
    double step, score, count;
  };
  std::vector<Candidate> fits, fallbacks;
  const int e0 = static_cast<int>(std::floor(std::log10(span / 12))) - 1, e1 = static_cast<int>(std::floor(std::log10(span / 2))) + 1;
  for (int e = e0; e <= e1; ++e) {
    for (auto [q, penalty] : {std::pair{1.0, 0.0}, std::pair{2.0, 0.25}, std::pair{2.5, 0.6}, std::pair{5.0, 0.25}}) {
      const double step = q * std::pow(10.0, e);
      if (!(step > 0) || !std::isfinite(step)) continue;
      if (r.integer && (step < 1 || step != std::floor(step))) continue;
      if (r.horizontal && q == 2.5) continue;   // side by side, 2.25 2.50 2.75 read worse than 2.2 2.4 2.6
      const double n = tickCount(lo, hi, step);
      if (n < 1) continue;
      double need = r.minGap;
      if (r.horizontal) {
        double w = 0;
        for (const std::string& l : tickLabels(tickValues(lo, hi, step), step)) w = std::max(w, textWidth(l));
        need += w;
      }
      const bool roomy = step / span * r.pixels >= need;
      Candidate c{step, std::fabs(n - target) + penalty, n};
      if (roomy && n >= 3 && n <= 10) fits.push_back(c);
      else if (roomy) fallbacks.push_back(c);
    }
  }
  auto better = [](const Candidate& a, const Candidate& b) { return a.score != b.score ? a.score < b.score : a.step > b.step; };
  if (!fits.empty()) return std::min_element(fits.begin(), fits.end(), better)->step;
  // Too little room for three ticks: as many as fit.
  if (!fallbacks.empty())
    return std::max_element(fallbacks.begin(), fallbacks.end(), [](const Candidate& a, const Candidate& b) { return a.count < b.count; })->step;
  return span;
}

TickAxis niceAxis(double lo, double hi, const TickRequest& r) {
  TickAxis a;
  if (!(lo <= hi)) lo = 0, hi = 1;   // no data (or NaN)
  lo = std::clamp(lo, -kLimit, kLimit);
  hi = std::clamp(hi, -kLimit, kLimit);
  if (r.integer) {
    // At least three integers: 5 -> 4..6, 0..1 -> 0..2, -1..0 -> -2..0.
    lo = std::floor(lo), hi = std::ceil(hi);
    if (hi - lo < 1) {
      lo -= 1, hi += 1;
    } else if (hi - lo < 2) {
      if (lo >= 0) hi += 1;
      else lo -= 1;
    }
  } else if (hi - lo <= std::max(std::fabs(lo), std::fabs(hi)) * 1e-12) {
    // A constant: a band of 10 % of its value either side (1 around zero).
    double mid = lo / 2 + hi / 2, d = mid == 0 ? 1 : std::fabs(mid) * 0.1;
    lo = mid - d, hi = mid + d;
  }
  if (r.pad) {
    double p = (hi / 2 - lo / 2) * 0.1;   // halves: no overflow near kLimit
    lo -= p, hi += p;
  }
  a.lo = lo, a.hi = hi;
  a.step = chooseStep(lo, hi, r);
  a.ticks = tickValues(lo, hi, a.step);
  a.labels = tickLabels(a.ticks, a.step);
  return a;
}

std::string formatSeconds(double v, double tolerance) {
  if (!std::isfinite(v)) return std::isnan(v) ? "NaN" : v > 0 ? "Inf" : "-Inf";
  if (std::fabs(v) >= 1e15) return fmt::format("{}", v);
  std::string s;
  for (int d = 0; d <= 9; ++d) {
    s = fmt::format("{:.{}f}", v, d);
    if (std::fabs(std::strtod(s.c_str(), nullptr) - v) <= tolerance) break;
  }
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

}  // namespace stc::plot

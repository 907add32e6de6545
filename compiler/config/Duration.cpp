#include "config/Duration.h"

#include <cstdint>

namespace stc::config {

namespace {

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }
bool digit(char c) { return c >= '0' && c <= '9'; }

// At most this much of the input is quoted in a message.
std::string shown(std::string_view s) {
  if (s.size() <= 40) return std::string(s);
  return std::string(s.substr(0, 37)) + "...";
}
// "'" + the input as shown, built by appending (GCC 12 at -O3 reports a false -Wrestrict
// for `"'" + std::string`, which inserts at the front).
std::string opened(std::string_view s) {
  std::string out(1, '\'');
  out += shown(s);
  return out;
}

struct Unit {
  const char* name;
  int64_t ns;
};
constexpr Unit kUnits[] = {{"d", 86'400'000'000'000}, {"h", 3'600'000'000'000}, {"m", 60'000'000'000}, {"s", 1'000'000'000},
                           {"ms", 1'000'000},         {"us", 1'000},            {"ns", 1}};

bool fail(std::string* why, std::string msg) {
  if (why) *why = std::move(msg);
  return false;
}

}  // namespace

bool parseDuration(std::string_view text, int64_t& out, std::string* why) {
  std::string_view t = text;
  // The prefix of a TIME / LTIME literal.
  for (std::string_view p : {"ltime#", "time#", "lt#", "t#"}) {
    if (t.size() < p.size()) continue;
    bool same = true;
    for (size_t i = 0; i < p.size() && same; ++i) same = lower(t[i]) == p[i];
    if (same) {
      t.remove_prefix(p.size());
      break;
    }
  }
  bool negative = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    negative = t[0] == '-';
    t.remove_prefix(1);
  }
  if (t.empty()) return fail(why, text.empty() ? "an empty duration" : opened(text) + "' has no number and unit (e.g. 10ms, 1.5s, 1h30m)");
  // Magnitude in nanoseconds, kept <= 2^63 (the magnitude of INT64_MIN).
  const unsigned __int128 limit = static_cast<unsigned __int128>(INT64_MAX) + (negative ? 1 : 0);
  unsigned __int128 total = 0;
  size_t lastUnit = 0;   // index into kUnits + 1 of the previous component
  size_t i = 0;
  while (i < t.size()) {
    // The number: digits with '_' between them, an optional fraction.
    const size_t start = i;
    unsigned __int128 whole = 0;
    bool overflow = false, anyDigit = false;
    std::string_view fraction;
    bool inFraction = false;
    size_t fracStart = 0;
    for (; i < t.size(); ++i) {
      const char c = t[i];
      if (digit(c)) {
        anyDigit = true;
        if (!inFraction) {
          whole = whole * 10 + static_cast<unsigned>(c - '0');
          if (whole > limit) overflow = true, whole = limit + 1;
        }
      } else if (c == '_') {
        if (i == start || !digit(t[i - 1]) || i + 1 >= t.size() || !digit(t[i + 1]))
          return fail(why, opened(text) + "': '_' only goes between digits");
      } else if (c == '.') {
        if (inFraction) return fail(why, opened(text) + "': a number has one decimal point at most");
        if (i == start || !digit(t[i - 1])) return fail(why, opened(text) + "': a digit is expected before '.'");
        inFraction = true;
        fracStart = i + 1;
      } else {
        break;
      }
    }
    if (inFraction) fraction = t.substr(fracStart, i - fracStart);
    if (!anyDigit) {
      if (i < t.size()) return fail(why, opened(text) + "': a number is expected before '" + std::string(1, t[i]) + "'");
      return fail(why, opened(text) + "': a number is expected");
    }
    if (inFraction && fraction.empty()) return fail(why, opened(text) + "': a digit is expected after '.'");
    // The unit.
    const size_t u0 = i;
    while (i < t.size() && lower(t[i]) >= 'a' && lower(t[i]) <= 'z') ++i;
    std::string unit;
    for (size_t k = u0; k < i; ++k) unit += lower(t[k]);
    if (unit.empty()) {
      if (i < t.size()) return fail(why, opened(text) + "': unexpected '" + std::string(1, t[i]) + "' (a unit d, h, m, s, ms, us or ns is expected)");
      return fail(why, opened(text) + "': the number has no unit (d, h, m, s, ms, us or ns; e.g. 10ms)");
    }
    size_t u = 0;
    while (u < std::size(kUnits) && unit != kUnits[u].name) ++u;
    if (u == std::size(kUnits)) return fail(why, opened(text) + "': unknown unit '" + shown(unit) + "' (d, h, m, s, ms, us or ns)");
    if (u + 1 <= lastUnit)
      return fail(why, opened(text) + "': units go from days down to nanoseconds, each at most once ('" + unit + "' after '" +
                           kUnits[lastUnit - 1].name + "')");
    lastUnit = u + 1;
    if (inFraction && i < t.size()) return fail(why, opened(text) + "': only the last component may have a fraction");
    if (overflow) return fail(why, opened(text) + "' is out of range (at most about 106751 days)");
    unsigned __int128 part = whole * static_cast<unsigned __int128>(kUnits[u].ns);
    // The fraction, truncated to whole nanoseconds (at most 14 digits matter for a day).
    unsigned __int128 num = 0, den = 1;
    for (size_t k = 0; k < fraction.size() && k < 18; ++k) {
      num = num * 10 + static_cast<unsigned>(fraction[k] - '0');
      den *= 10;
    }
    part += num * static_cast<unsigned __int128>(kUnits[u].ns) / den;
    total += part;
    if (part > limit || total > limit) return fail(why, opened(text) + "' is out of range (at most about 106751 days)");
    // IEC 61131-3 allows '_' between components: T#1h_30m.
    if (i + 1 < t.size() && t[i] == '_' && digit(t[i + 1])) ++i;
  }
  out = negative ? static_cast<int64_t>(0 - static_cast<uint64_t>(total)) : static_cast<int64_t>(static_cast<uint64_t>(total));
  return true;
}

bool parseDuration(std::string_view text, DurationSign sign, int64_t& out, std::string* why) {
  int64_t v = 0;
  if (!parseDuration(text, v, why)) return false;
  if (sign == DurationSign::NonNegative && v < 0) return fail(why, opened(text) + "' is negative (a duration >= 0 is expected)");
  if (sign == DurationSign::Positive && v <= 0) return fail(why, opened(text) + "' is not positive (a duration > 0 is expected)");
  out = v;
  return true;
}

std::string formatDuration(int64_t ns) {
  std::string out = "T#";
  uint64_t rest = static_cast<uint64_t>(ns);
  if (ns < 0) {
    out += '-';
    rest = 0 - rest;
  }
  if (rest == 0) return out + "0s";
  for (const Unit& u : kUnits) {
    const uint64_t n = rest / static_cast<uint64_t>(u.ns);
    if (n == 0) continue;
    rest -= n * static_cast<uint64_t>(u.ns);
    out += std::to_string(n) + u.name;
  }
  return out;
}

}  // namespace stc::config

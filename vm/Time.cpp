#include "vm/Time.h"

#include <string>

namespace stc::vm {

std::string formatIecTime(Time t, std::string_view prefix) {
  std::string out(prefix);
  // Work in unsigned so INT64_MIN has a magnitude.
  uint64_t rest = static_cast<uint64_t>(t);
  if (t < 0) {
    out += '-';
    rest = 0 - rest;
  }
  if (rest == 0) return out + "0s";
  struct Unit { uint64_t ns; const char* suffix; };
  static constexpr Unit kUnits[] = {
      {86'400'000'000'000, "d"}, {3'600'000'000'000, "h"}, {60'000'000'000, "m"},
      {1'000'000'000, "s"},      {1'000'000, "ms"},         {1'000, "us"},
      {1, "ns"}};
  for (const Unit& u : kUnits) {
    uint64_t n = rest / u.ns;
    if (n == 0) continue;
    rest -= n * u.ns;
    out += std::to_string(n);
    out += u.suffix;
  }
  return out;
}

std::string formatSeconds(Time t) {
  uint64_t mag = static_cast<uint64_t>(t);
  std::string out;
  if (t < 0) {
    out += '-';
    mag = 0 - mag;
  }
  out += std::to_string(mag / 1'000'000'000);
  uint64_t frac = mag % 1'000'000'000;
  if (frac == 0) return out;
  std::string digits = std::to_string(frac);
  digits.insert(0, 9 - digits.size(), '0');
  digits.erase(digits.find_last_not_of('0') + 1);
  return out + '.' + digits;
}

bool parseIecDuration(std::string_view text, Time& out) {
  std::string t;
  for (char c : text)
    if (c != '_' && c != ' ') t += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  for (const char* p : {"ltime#", "time#", "lt#", "t#"})
    if (t.rfind(p, 0) == 0) { t = t.substr(std::string_view(p).size()); break; }
  bool neg = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) { neg = t[0] == '-'; t = t.substr(1); }
  if (t.empty()) return false;
  long double total = 0;
  size_t i = 0;
  while (i < t.size()) {
    size_t j = i;
    while (j < t.size() && ((t[j] >= '0' && t[j] <= '9') || t[j] == '.')) ++j;
    if (j == i) return false;
    long double n = std::stold(t.substr(i, j - i));
    size_t u = j;
    while (u < t.size() && t[u] >= 'a' && t[u] <= 'z') ++u;
    std::string unit = t.substr(j, u - j);
    long double f = unit == "d" ? 86'400e9L : unit == "h" ? 3'600e9L : unit == "m" ? 60e9L : unit == "s" ? 1e9L
                    : unit == "ms" ? 1e6L : unit == "us" ? 1e3L : unit == "ns" ? 1.0L : 0;
    if (f == 0) return false;
    total += n * f;
    i = u;
  }
  out = static_cast<Time>(neg ? -total : total);
  return true;
}

}  // namespace stc::vm

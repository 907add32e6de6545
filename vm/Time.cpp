#include "vm/Time.h"

#include <string>

#include "config/Duration.h"

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
  // Blanks around the literal are allowed here (STRING_TO_TIME('  T#5ms')), not inside.
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return config::parseDuration(text, out);
}

}  // namespace stc::vm

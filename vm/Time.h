// Simulated time of the virtual controller: signed nanoseconds from the start
// of the run.  TIME, LTIME and the date types share this representation.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace stc::vm {

using Time = int64_t;

inline constexpr Time kNanosecond = 1;
inline constexpr Time kMicrosecond = 1'000;
inline constexpr Time kMillisecond = 1'000'000;
inline constexpr Time kSecond = 1'000'000'000;

// `T#1s500ms`, `T#0s`, `T#-250ms`: components d h m s ms us ns, zeros left
// out.  `prefix` is `LTIME#` for LTIME values.
std::string formatIecTime(Time t, std::string_view prefix = "T#");

// Seconds as an exact decimal without exponent or trailing zeros: `0`,
// `0.001`, `1.5`, `-2.000000001` (trace time stamps).
std::string formatSeconds(Time t);

// Parses a duration: T#1s500ms, TIME#-2m, LTIME#5us, 1d2h, 250ms, 1.5s (a
// fraction on the last component).  False if the text is not a duration.
// The grammar is config::parseDuration's (compiler/config/Duration.h).
bool parseIecDuration(std::string_view text, Time& out);

}  // namespace stc::vm

// The one duration parser of stc: the command line (--for, --interval,
// --watchdog ...), project.toml, scenarios and the controller's string
// conversions all read durations here (docs/projects.md, "Durations").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace stc::config {

// Parses the text of an ST TIME literal, with or without its prefix:
//   [T#|TIME#|LT#|LTIME#] [+|-] component {component}
//   component = digits ['.' digits] unit,  unit = d | h | m | s | ms | us | ns
// (case-insensitive; '_' between digits and between components; units from days down to
// nanoseconds, each at most once; a fraction only on the last component,
// truncated to whole nanoseconds).  Examples: 10ms, 1.5s, 1h30m, T#2m3s,
// LTIME#-5us.  On success writes nanoseconds to `out` and returns true;
// otherwise returns false and, when `why` is given, writes what is wrong
// ("a number is expected before 's'", "more than 106751d23h47m16s854ms775us807ns" ...).
// Never throws; any input length.
bool parseDuration(std::string_view text, int64_t& out, std::string* why = nullptr);

// parseDuration plus a sign rule: "must not be negative" / "must be positive".
enum class DurationSign { Any, NonNegative, Positive };
bool parseDuration(std::string_view text, DurationSign sign, int64_t& out, std::string* why);

// `T#1s500ms`, `T#0s`, `T#-250ms`: the ST literal of a duration (what the
// [[task]] tables of project.toml become).
std::string formatDuration(int64_t ns);

}  // namespace stc::config

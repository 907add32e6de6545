// The memory image seen from outside: symbolic paths (MAIN.fb.Q, GVL.x,
// arr[3].x) resolved to offsets and types, and values printed as IEC
// literals.  Used by --watch, traces and retain.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "codegen/CodeGen.h"

namespace stc::sema { class Layout; class Type; }

namespace stc::vm {

struct ValueRef {
  uint64_t offset = 0;                 // from the image base
  const sema::Type* type = nullptr;
  bool retain = false, persistent = false;
  bool constant = false;               // the root is a CONSTANT
  int bit = -1;                        // a BOOL view of one bit
  // The path crosses or holds an {attribute 'mirrored'} struct: whoever reads it
  // needs the natives to keep those structs current (RunOptions::observesMirrored).
  bool mirrored = false;
};

// Resolves `path` (case-insensitive).  On failure `error` says why, with a
// "did you mean" when a close name exists.
bool resolvePath(const codegen::ImageMap& map, const sema::Layout& layout, const std::string& path, ValueRef& out, std::string& error);

// The value at `p` as an IEC literal: TRUE, 42, 16#FF, 3.5, T#1s500ms,
// 'text', Color#Red, [1, 2], (x := 1, y := 2).
std::string formatValue(const uint8_t* p, const sema::Type* t, const sema::Layout& layout);

// The inverse of formatValue for elementary types, enums and subranges:
// parses the ST literal `text` as a value of type `t` and stores it at `p`
// (the type's size; a BOOL is one byte).  Accepts TRUE/FALSE (also 1/0),
// integers (16#FF, 2#1010, -5, 1_000, typed INT#5), REAL literals, durations
// (T#1s500ms, 250ms), D#/TOD#/DT# dates, 'strings' / "wstrings" with $
// escapes, Color#Red or Red (enums), and checks the range.  False with
// `error` (nothing stored) otherwise.  Used by stc test (scenario stimuli
// and checks).
bool parseValue(std::string_view text, uint8_t* p, const sema::Type* t, const sema::Layout& layout, std::string& error);

// Shortest round-trip text of a REAL/LREAL with a '.' or an exponent.
std::string formatReal(double v, bool single);

// Dates as nanoseconds since 1970-01-01 (proleptic Gregorian calendar).
std::string formatDate(int64_t ns);          // 2024-02-29
std::string formatTimeOfDay(int64_t ns);     // 12:30:15.5
int64_t daysFromCivil(int64_t y, unsigned m, unsigned d);
void civilFromDays(int64_t days, int64_t& y, unsigned& m, unsigned& d);
// Parses D#/DATE#/LDATE#, TOD#/TIME_OF_DAY#/LTOD#, DT#/DATE_AND_TIME#/LDT# text (the
// prefix optional when `kind` says which: 'D', 'T' (time of day), 'S' (date and time)).
bool parseDateText(std::string_view text, char kind, int64_t& ns);

}  // namespace stc::vm

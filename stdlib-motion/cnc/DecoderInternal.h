// Internal to the decoder's .cpp files: limits, word masks, G-code groups.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "stdlib-motion/cnc/Element.h"
#include "stdlib-motion/cnc/Parser.h"

namespace stc::cnc::detail {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxCoord = 1e9;      // coordinates, centres, radii, distances, D
constexpr double kMaxPosition = 1e10;  // a position after offsets and increments
constexpr double kMaxFeed = 1e9;       // F, FF
constexpr double kMaxAccel = 1e12;     // E, E-, EF, EF-
constexpr double kMaxDwell = 1e6;      // s
constexpr double kMaxSweep = 36000;    // deg (100 turns)

constexpr uint32_t B(char c) { return bit(c); }
constexpr uint32_t kAxesMask =
    B('X') | B('Y') | B('Z') | B('A') | B('B') | B('C') | B('P') | B('Q') | B('U') | B('V') | B('W');
constexpr uint32_t kIJK = B('I') | B('J') | B('K');
constexpr uint32_t kModalMask = B('F') | B('E') | (1u << SlotEMinus) | (1u << SlotFF) | (1u << SlotEF) |
                                (1u << SlotEFMinus) | B('S');
constexpr char kAxisLetters[kAxisCount] = {'X', 'Y', 'Z', 'A', 'B', 'C', 'P', 'Q', 'U', 'V', 'W'};

enum class Group : uint8_t { Motion, Other, Offset, Plane, Dist, Centre, Tool, Smooth, Loop };

inline Group groupOf(int g) {
  switch (g) {
    case 0: case 1: case 2: case 3: case 5: case 6: case 8: case 9: case 10: return Group::Motion;
    case 53: case 54: case 55: case 56: return Group::Offset;
    case 16: case 17: case 18: case 19: return Group::Plane;
    case 90: case 91: return Group::Dist;
    case 98: case 99: return Group::Centre;
    case 40: case 41: case 42: return Group::Tool;
    case 50: case 51: case 52: return Group::Smooth;
    case 60: case 61: return Group::Loop;
    default: return Group::Other;   // 4, 20, 25, 36, 37, 75, 92
  }
}

// The words a travel command reads (besides the modal F/E/S words).
inline uint32_t motionMask(int g) {
  switch (g) {
    case 2: case 3: return kAxesMask | kIJK | B('R') | B('T');
    case 6: return kAxesMask | B('I') | B('J');
    case 8: case 9: return kAxesMask | kIJK | B('R');
    default: return kAxesMask;
  }
}
inline uint32_t otherMask(int g) {
  switch (g) {
    case 4: return B('T');
    case 20: case 25: return B('L') | B('K');
    case 36: case 37: return B('O') | B('D');
    case 92: return kAxesMask;
    default: return 0;
  }
}

inline std::string gName(int g) { return "G" + std::to_string(g); }

inline int lowestBit(uint32_t m) { return __builtin_ctz(m); }

// Wraps an angle difference into the sweep of a counter-clockwise (0, 2pi] or
// clockwise [-2pi, 0) arc.
inline double sweepOf(double d, bool ccw) {
  const double two = 2 * kPi;
  if (ccw) {
    d = std::fmod(d, two);
    if (d <= 0) d += two;
  } else {
    d = std::fmod(d, two);
    if (d >= 0) d -= two;
  }
  return d;
}


}  // namespace stc::cnc::detail

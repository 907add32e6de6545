// Plausibility bounds of the numbers a user gives a motion command.  A value
// beyond them is refused like a NaN (the FB's invalid-parameter ErrorID), so a
// typo such as Velocity := 1.0E308 never reaches the planner or a motor.  The
// bounds are far beyond any real machine in any unit (docs/motion.md, "Bad values").
#pragma once

#include <cmath>

namespace stc::motion::bounds {

inline constexpr double kVelocity = 1e9;       // u/s
inline constexpr double kRate = 1e12;          // acceleration, deceleration [u/s^2]
inline constexpr double kJerk = 1e15;          // u/s^3
inline constexpr double kPosition = 1e12;      // positions and distances [u]

inline bool velocity(double v) { return std::isfinite(v) && v > 0 && v <= kVelocity; }
inline bool signedVelocity(double v) { return std::isfinite(v) && std::fabs(v) <= kVelocity; }
inline bool rate(double a) { return std::isfinite(a) && a > 0 && a <= kRate; }
inline bool jerk(double j) { return std::isfinite(j) && j >= 0 && j <= kJerk; }
inline bool position(double x) { return std::isfinite(x) && std::fabs(x) <= kPosition; }

}  // namespace stc::motion::bounds

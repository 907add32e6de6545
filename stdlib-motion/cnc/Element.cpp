#include "stdlib-motion/cnc/Element.h"

namespace stc::cnc {

char axisLetter(Axis a) {
  static constexpr char kLetters[kAxisCount + 1] = "XYZABCPQUVW";
  return a < kAxisCount ? kLetters[a] : '?';
}

const char* toString(MoveType t) {
  switch (t) {
    case MoveType::Lin: return "LIN";
    case MoveType::Clw: return "CLW";
    case MoveType::Cclw: return "CCLW";
    case MoveType::Spline: return "SPLINE";
    case MoveType::Parabola: return "PARABOLA";
    case MoveType::EllClw: return "ELLCLW";
    case MoveType::EllCclw: return "ELLCCLW";
    case MoveType::LinPos: return "LINPOS";
    case MoveType::InitPos: return "INITPOS";
    case MoveType::MCommand: return "MCOMMAND";
    case MoveType::Dwell: return "DWELL";
    case MoveType::Sync: return "SYNC";
  }
  return "?";
}

bool isToolPath(MoveType t) {
  switch (t) {
    case MoveType::Lin:
    case MoveType::Clw:
    case MoveType::Cclw:
    case MoveType::Spline:
    case MoveType::Parabola:
    case MoveType::EllClw:
    case MoveType::EllCclw:
      return true;
    default:
      return false;
  }
}

bool isMotion(MoveType t) { return isToolPath(t) || t == MoveType::LinPos; }

const char* toString(Plane p) {
  switch (p) {
    case Plane::XY: return "XY";
    case Plane::ZX: return "ZX";
    case Plane::YZ: return "YZ";
    case Plane::Free: return "free";
  }
  return "?";
}

}  // namespace stc::cnc

// The SMC_ERROR numbers of the core's faults, and their names and descriptions
// (SMC_ErrorString).  Free of the generated header, so the unit tests can link
// Sm3ErrorText.cpp alone.
#pragma once

#include <cstdint>
#include <string>

#include "stdlib-motion/core/Errors.h"

namespace stc::motion::sm3face {

// The SMC_ERROR number a CODESYS SoftMotion controller reports for fault e (0 for None).
uint16_t smcError(Error e);

// "<SMC_ERROR name>: <description>" from the manuals' table; null for an unknown number.
const char* errorName(uint16_t id);
const char* errorDescription(uint16_t id);
std::string errorString(uint16_t id);   // "unknown SMC_ERROR <n>" for an unknown number

}  // namespace stc::motion::sm3face

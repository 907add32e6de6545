// The core's faults carry no vendor numbers; each face maps them.  These tests pin
// the SM3 face's table (every fault has its own SMC_ERROR number, with a name and a
// text for SMC_ErrorString) and the classes that coarser faces number by.
#include <gtest/gtest.h>

#include <set>

#include "stdlib-motion/codesys_sm3/Sm3ErrorText.h"
#include "stdlib-motion/core/Errors.h"

using namespace stc::motion;

TEST(Faults, EverySm3NumberIsDistinctAndNamed) {
  EXPECT_EQ(sm3face::smcError(Error::None), 0);
  std::set<uint16_t> seen;
  for (uint16_t i = 1; i < static_cast<uint16_t>(Error::Count_); ++i) {
    const Error e = static_cast<Error>(i);
    const uint16_t n = sm3face::smcError(e);
    EXPECT_NE(n, 0) << "fault " << i;
    EXPECT_TRUE(seen.insert(n).second) << "SMC_ERROR " << n << " twice";
    if (n < 0x7000) {
      EXPECT_NE(sm3face::errorName(n), nullptr) << "SMC_ERROR " << n << " has no name";
    }
  }
  // Spot checks against the manual's table (spec/amc1600c.md, appendix 3).
  EXPECT_EQ(sm3face::smcError(Error::MaInvalidVelAcc), 201);
  EXPECT_EQ(sm3face::smcError(Error::NotReadyForMotion), 34);
  EXPECT_EQ(sm3face::smcError(Error::CiScalingIncorrect), 628);
  EXPECT_EQ(sm3face::smcError(Error::RcamFileDoesntExist), 2200);
}

TEST(Faults, EveryFaultHasAClass) {
  EXPECT_EQ(faultClass(Error::None), FaultClass::None);
  for (uint16_t i = 1; i < static_cast<uint16_t>(Error::Count_); ++i)
    EXPECT_NE(faultClass(static_cast<Error>(i)), FaultClass::None) << "fault " << i;
  EXPECT_EQ(faultClass(Error::MrInvalidVelAcc), FaultClass::InvalidParameter);
  EXPECT_EQ(faultClass(Error::NotReadyForMotion), FaultClass::WrongState);
  EXPECT_EQ(faultClass(Error::BufferFull), FaultClass::QueueFull);
  EXPECT_EQ(faultClass(Error::FollowingError), FaultClass::AxisFault);
  EXPECT_EQ(faultClass(Error::TpCommError), FaultClass::Communication);
  EXPECT_EQ(faultClass(Error::AdlFileCannotBeOpened), FaultClass::File);
}

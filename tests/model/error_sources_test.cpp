// The error layout's harmonic orders: 0..kMaxHarmonicOrder (16) accepted, with 2N+1 values per dynamic
// channel; others refused with a message naming the range.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "ccal/model/error_sources.hpp"

namespace ccal {
namespace {

TEST(ErrorLayout, HarmonicOrdersUpToSixteen) {
  EXPECT_EQ(kMaxHarmonicOrder, 16);
  const ErrorLayout widest(16);
  EXPECT_EQ(widest.harmonic_order(), 16);
  EXPECT_EQ(widest.size(), kStaticChannelCount + kDynamicChannelCount * 33);
  EXPECT_TRUE(widest.find_parameter("dx3_s16").has_value());
  EXPECT_FALSE(widest.find_parameter("dx3_s17").has_value());
  EXPECT_EQ(ErrorLayout(0).size(), kStaticChannelCount + kDynamicChannelCount);
  for (const int order : {17, -1, 64}) {
    try {
      static_cast<void>(ErrorLayout(order));
      ADD_FAILURE() << "accepted harmonic order " << order;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()),
                "harmonic order must be between 0 and 16, got " + std::to_string(order));
    }
  }
}

}  // namespace
}  // namespace ccal

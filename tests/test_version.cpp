#include <gtest/gtest.h>

#include <string>

#include "ccal/version.hpp"

TEST(Version, IsSemantic) { EXPECT_EQ(std::string(ccal::version()), "0.1.0"); }

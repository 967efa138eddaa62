// The lists of names in the fit's and the observability's messages: "A", "A and B", "A, B and C".
#include <gtest/gtest.h>

#include "../src/reduction/text_lists.hpp"

namespace ccal::detail {
namespace {

TEST(JoinNames, CommasThenAndBeforeTheLast) {
  EXPECT_EQ(join_names({}), "");
  EXPECT_EQ(join_names({"K0"}), "K0");
  EXPECT_EQ(join_names({"K0", "K2"}), "K0 and K2");
  EXPECT_EQ(join_names({"K0", "K2", "K3"}), "K0, K2 and K3");
  EXPECT_EQ(join_names({"K0", "K1", "K2", "K3"}), "K0, K1, K2 and K3");
}

}  // namespace
}  // namespace ccal::detail

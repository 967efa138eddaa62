// The measuring chain's parameter codes (setup/measuring_chain.hpp): every input's code above every layout index
// and rate-noise code, and back to its id.
#include "ccal/setup/measuring_chain.hpp"

#include <gtest/gtest.h>

#include "ccal/model/error_sources.hpp"

namespace ccal {
namespace {

TEST(MeasuringChain, CodesRoundTripToTheirIds) {
  MeasuringChain chain;
  chain.declared.push_back({"temperature", "", "K", {{"K0", 1.0}}});
  const std::vector<std::string> fixed{"K1"};
  for (const std::string id : {"g", "time_base", "output_gain", "output_offset", "K1", "encoder1_c1",
                               "encoder3_s16", "temperature"}) {
    const auto code = find_chain_input(id, chain, fixed, kMaxHarmonicOrder);
    ASSERT_TRUE(code.has_value()) << id;
    EXPECT_TRUE(is_chain_parameter(*code)) << id;
    EXPECT_GT(*code, ErrorLayout(kMaxHarmonicOrder).size());
    EXPECT_EQ(chain_input_id(*code, chain), id);
  }
  // Not an input: a free term, an encoder above the order, a malformed encoder id, a layout id.
  EXPECT_FALSE(find_chain_input("K0", chain, fixed, 1));
  EXPECT_FALSE(find_chain_input("encoder1_c2", chain, fixed, 1));
  EXPECT_FALSE(find_chain_input("encoder2_c1", chain, fixed, 1));
  EXPECT_FALSE(find_chain_input("encoder1_c", chain, fixed, 1));
  EXPECT_FALSE(find_chain_input("dthz5", chain, fixed, 1));
  EXPECT_FALSE(is_chain_parameter(-1));  // a run's rate noise
  for (int drive : {1, 3})
    for (int k = 1; k <= kMaxHarmonicOrder; ++k)
      for (bool sine : {false, true}) {
        const EncoderTerm t = encoder_term(encoder_index({drive, k, sine}));
        EXPECT_EQ(t.drive, drive);
        EXPECT_EQ(t.harmonic, k);
        EXPECT_EQ(t.is_sine, sine);
      }
}

}  // namespace
}  // namespace ccal

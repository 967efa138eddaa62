// An ill-posed fit is a user-input error (InputError, exit code 2 at the command line) that names the terms
// involved, so that front ends can say what would help without reading the message's text.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/verbs/identification.hpp"

namespace {

using ccal::FitProblem;
using ccal::IllPosedFit;

// y = K0 + K2 x² + K3 x³ sampled at x ∈ {1, 2}: three terms, two observations.
FitProblem two_levels() {
  FitProblem p;
  p.term_names = {"K0", "K2", "K3"};
  p.H.resize(2, 3);
  p.H << 1, 1, 1, 1, 4, 8;
  p.y = Eigen::Vector2d(1, 2);
  return p;
}

TEST(IllPosedFit, IsAnInputErrorNamingTheTerms) {
  try {
    ccal::fit(two_levels());
    FAIL() << "expected IllPosedFit";
  } catch (const ccal::InputError& e) {
    const auto* ill = dynamic_cast<const IllPosedFit*>(&e);
    ASSERT_NE(ill, nullptr) << e.what();
    EXPECT_EQ(ill->terms(), (std::vector<std::string>{"K0", "K2", "K3"}));
  }
}

TEST(IllPosedFit, DependentColumnsNameOnlyTheDependentTerms) {
  // The K3 column is twice the K2 column: K2 and K3 cannot be separated, K0 is a bystander.
  FitProblem p;
  p.term_names = {"K0", "K2", "K3"};
  p.H.resize(4, 3);
  p.H << 1, 1, 2, 1, 2, 4, 1, 3, 6, 1, 4, 8;
  p.y = Eigen::Vector4d(1, 2, 3, 5);
  try {
    ccal::fit(p);
    FAIL() << "expected IllPosedFit";
  } catch (const IllPosedFit& e) {
    EXPECT_EQ(e.terms(), (std::vector<std::string>{"K2", "K3"})) << e.what();
  }
}

TEST(IllPosedFit, PlanCannotIdentifyPrefixesTheMessageAndKeepsTheTerms) {
  const IllPosedFit fit_error("K2 and K3 are dependent", {"K2", "K3"});
  const IllPosedFit e = ccal::plan_cannot_identify(fit_error);
  EXPECT_STREQ(e.what(), "the test plan cannot identify the configured terms: K2 and K3 are dependent");
  EXPECT_EQ(e.terms(), (std::vector<std::string>{"K2", "K3"}));
}

TEST(IllPosedFit, HintFollowsTheTermsInvolved) {
  // Powers of a_i: more g-levels; terms in a_p or a_o: another mounting; neither: nothing.
  EXPECT_NE(ccal::verbs::ill_posed_hint({"K2", "K3"}).find("g-level"), std::string::npos);
  EXPECT_NE(ccal::verbs::ill_posed_hint({"K_p"}).find("mounting"), std::string::npos);
  EXPECT_EQ(ccal::verbs::ill_posed_hint({}), "");
}

}  // namespace

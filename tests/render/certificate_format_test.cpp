// Figures and units as the certificate writes them: typeset units, numbers without e-notation, ν_eff as an
// integer or ∞, k to two decimals, the interval's method named, files without their folders.
#include <gtest/gtest.h>

#include "../src/render/certificate_parts.hpp"

namespace ccal::render::certificate_parts {
namespace {

TEST(CertificateFormat, UnitsAreTypeset) {
  EXPECT_EQ(unit_html("deg/s/g^2"), "°/s/g²");
  EXPECT_EQ(unit_html("deg/s/gn^3"), "°/s/g<sub>n</sub>³");
  EXPECT_EQ(unit_html("um"), "µm");
  EXPECT_EQ(unit_html("arcsec"), "″");
  EXPECT_EQ(unit_html("m/(rad/s)^2"), "m/(rad/s)²");
  EXPECT_EQ(unit_html("deg/s/rtHz"), "°/s/√Hz");
  EXPECT_EQ(unit_html("s^-1"), "s⁻¹");
  EXPECT_EQ(unit_html("g^10"), "g¹⁰");
  EXPECT_EQ(unit_html("a<b"), "a&lt;b");  // the rest escaped
  // whole words only: "mdeg" and "drum" are no degrees or micrometres
  EXPECT_EQ(unit_html("mdeg"), "mdeg");
}

TEST(CertificateFormat, NamesInWordsAreTypeset) {
  EXPECT_EQ(words_html("arm stretch c, dR_d = c*Omega^2"), "arm stretch c, dR_d = c·Ω²");
  EXPECT_EQ(words_html("platform rate ripple, cos gamma"), "platform rate ripple, cos γ");
  EXPECT_EQ(words_html("main-axis rate error <x>"), "main-axis rate error &lt;x&gt;");
  EXPECT_EQ(words_html("omegas"), "omegas");  // whole words only
}

TEST(CertificateFormat, NumbersArePlainOrPowersOfTen) {
  EXPECT_EQ(number_html(0.0018, 2), "<span class=\"nowrap\">0.0018</span>");
  EXPECT_EQ(number_html(-298.4, 3), "<span class=\"nowrap\">−298</span>");
  EXPECT_EQ(number_html(1.497e-05, 2), "<span class=\"nowrap\">1.5 × 10⁻⁵</span>");  // leading zeros dropped
  EXPECT_EQ(number_html(-2.5e12, 2), "<span class=\"nowrap\">−2.5 × 10¹²</span>");
  EXPECT_EQ(number_html(123456, 2),
            "<span class=\"nowrap\">1.2 × 10⁵</span>");  // %g's exponent form, typeset
  EXPECT_EQ(number_html(1e-10, 1), "<span class=\"nowrap\">1 × 10⁻¹⁰</span>");
  EXPECT_EQ(number_html(0, 2), "0");
}

TEST(CertificateFormat, DegreesOfFreedomAndCoverageFactor) {
  EXPECT_EQ(dof_text(Json(nullptr)), "∞");
  EXPECT_EQ(dof_text(Json(44010.7)), "44010");  // the quantile is taken at ⌊ν⌋: the integer below
  EXPECT_EQ(dof_text(Json(12.0)), "12");
  EXPECT_EQ(coverage_factor_text(1.959963984540054), "1.96");
  EXPECT_EQ(coverage_factor_text(2.0), "2.00");
  EXPECT_EQ(coverage_factor_text(2.2281388519649385), "2.23");
}

TEST(CertificateFormat, TheMethodIsNamedByHowTheIntervalIsObtained) {
  EXPECT_EQ(method_html(Json{{"interval_method", "student_t"}, {"effective_dof", nullptr}}),
            "normal (ν<sub>eff</sub> = ∞)");
  EXPECT_EQ(method_html(Json{{"interval_method", "student_t"}, {"effective_dof", 12.6}}),
            "Student's t at ν<sub>eff</sub> = 12");
  EXPECT_EQ(method_html(Json{{"interval_method", "monte_carlo"}, {"effective_dof", 12.6}}),
            "Monte Carlo (JCGM 101)");
  // A stated k: read in the normal distribution, or in Student's t, whose coverage at k is then lower.
  EXPECT_EQ(method_html(Json{{"interval_method", "coverage_factor"},
                             {"effective_dof", nullptr},
                             {"stated_coverage_probability", {{"normal", 0.9545}, {"student_t", nullptr}}}}),
            "stated k, normal (ν<sub>eff</sub> = ∞)");
  EXPECT_EQ(method_html(Json{{"interval_method", "coverage_factor"},
                             {"effective_dof", 10.4},
                             {"stated_coverage_probability", {{"normal", 0.9545}, {"student_t", 0.92661}}}}),
            "stated k, Student's t at ν<sub>eff</sub> = 10, coverage probability 93 %");
}

TEST(CertificateFormat, TermsFilesAndPercentages) {
  EXPECT_EQ(term_html("K0"), "K<sub>0</sub>");
  EXPECT_EQ(term_html("K_oq"), "K<sub>oq</sub>");
  EXPECT_EQ(base_name("/home/lab/run 7/obs.csv"), "obs.csv");
  EXPECT_EQ(base_name("obs.csv"), "obs.csv");
  EXPECT_EQ(percent_text(0.95), "95 %");
  EXPECT_EQ(percent_text(0.9973), "99.73 %");
  // what a stated k gives, rounded as EA-4/02 words it: "approximately 95 %" for k = 2
  EXPECT_EQ(approximate_percent_text(0.9544997361036416), "95 %");
  EXPECT_EQ(approximate_percent_text(0.9973002039367398), "99.7 %");
}

}  // namespace
}  // namespace ccal::render::certificate_parts

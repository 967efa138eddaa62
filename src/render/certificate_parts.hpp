#pragma once
// Pieces of the calibration certificate (private to the library): figures and units as a customer reads them,
// and the certificate's sections. Every figure is the calibration statement's (doc "identify": the JSON of
// `ccal identify OBS.csv --statement --config CONFIG`), rounded; no command, option, key or path is written.
#include <string>
#include <string_view>
#include <vector>

#include "ccal/render/report.hpp"
#include "report_html.hpp"

namespace ccal::render::certificate_parts {

using report_html::Doc;
using report_html::Json;

// A unit as typeset HTML: deg → °, um → µm, arcsec → ″, rtHz → √Hz, gn → g<sub>n</sub>, ^2 → ², the rest
// escaped ("deg/s/g^2" → "°/s/g²").
std::string unit_html(std::string_view unit);
// A quantity's name in words as typeset HTML: Greek letters for their names (Omega → Ω, theta → θ), ^2 → ²,
// * → ·, the rest escaped ("arm stretch c, dR_d = c*Omega^2" → "arm stretch c, dR_d = c·Ω²").
std::string words_html(std::string_view text);
// A number with `digits` significant digits, in plain notation from 1e-4 to 1e6, else as m × 10ⁿ with
// the exponent a superscript; U+2212 for a minus sign; never broken over lines.
std::string number_html(double value, int digits);
// Degrees of freedom as the certificate writes them: ∞ for an infinite one (JSON null), else the integer
// below (the Student t quantile is taken at ⌊ν⌋).
std::string dof_text(const Json& dof);
// A coverage factor to the digits that matter: two decimals (1.96, 2.00).
std::string coverage_factor_text(double k);
// How a coefficient's interval was obtained: "normal (ν_eff = ∞)", "Student's t at ν_eff = 12" or
// "Monte Carlo (JCGM 101)", in HTML. The result on page 1 and the annex both write it from here.
std::string method_html(const Json& coefficient);
// A term id as typeset HTML: K0 → K<sub>0</sub>, K_oq → K<sub>oq</sub>.
std::string term_html(std::string_view id);
// A coverage probability as a percentage ("95 %").
std::string percent_text(double p);
// A coverage probability a stated k gives, as a certificate rounds it ("95 %" for 0.9545).
std::string approximate_percent_text(double p);
// A file's name without its folder.
std::string base_name(std::string_view path);

// The sections (certificate_result.cpp, certificate_annex.cpp).
std::string result_section(const Doc& identify);
std::string model_section(const verbs::ReportResult& r, const Doc& identify);
std::string method_section(const verbs::ReportResult& r, const Doc& identify);
std::string traceability_section(const verbs::ReportResult& r, const Doc& budget);
// Annex A: the uncertainty budget of each coefficient as a GUM table; annex B: the runs.
std::string budget_annex(const Doc& identify, const Doc& budget);
std::string runs_annex(const verbs::ReportResult& r, const Doc& identify);

}  // namespace ccal::render::certificate_parts

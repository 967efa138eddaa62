#pragma once
// Pieces shared by the reports of several verbs (private to the library): the observability and
// identification sections, the covariance of several instruments' coefficients, as JSON values and text.
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/verbs/identification.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "ccal/verbs/observability_report.hpp"

namespace ccal::render {

nlohmann::ordered_json observability_json(const verbs::ObservabilityReport& report);
std::string observability_text(const verbs::ObservabilityReport& report);
nlohmann::ordered_json identification_json(const verbs::Identification& id);
std::string identification_text(const verbs::Identification& id);
// A number of degrees of freedom as the outputs write it: null for ∞ (a value taken as exact).
nlohmann::ordered_json dof_json(double dof);
// The covariance of a test's instruments' coefficients (reduce, budget): the matrices by rows and the LPU's
// correlation; as text, the correlation table (the Monte Carlo's in brackets where it ran).
nlohmann::ordered_json covariance_json(const verbs::InstrumentCovariance& covariance);
std::string covariance_text(const verbs::InstrumentCovariance& covariance);
// One instrument's part of a test's JSON: {"id", then the fields of its own report but command, ccal_version and
// config, which the test's report gives once}.
nlohmann::ordered_json instrument_part_json(const std::string& id, const nlohmann::ordered_json& whole);

}  // namespace ccal::render

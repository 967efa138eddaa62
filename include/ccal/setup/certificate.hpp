#pragma once
// The administrative part of a calibration certificate (the configuration's optional [certificate] table,
// docs/config.md): what was calibrated, for whom, by whom, when, where, under which conditions, by which
// procedure and against which traceable standards (ISO/IEC 17025 §7.8.2 lists what a certificate carries).
// The figures of the certificate come from the calibration statement (verbs/statement.hpp); these fields are
// text, shown as written. Every field is optional; the dates are calendar dates (YYYY-MM-DD).

#include <array>
#include <string>
#include <utility>
#include <vector>
#include <string_view>

namespace ccal {

struct Certificate {
  std::string number;               // the certificate's identification, e.g. "CAL-2026-0142"
  // ISO/IEC 17025 §7.8.8: an amended or reissued certificate carries its revision and the number of the
  // certificate it replaces ("" for a first issue).
  std::string revision;             // e.g. "1"
  std::string replaces;             // the number of the certificate this one replaces
  std::string laboratory;           // name and address of the calibration laboratory
  std::string accreditation;        // accreditation body and number, if any
  std::string customer;             // name and address of the customer
  std::string instrument;           // the item calibrated: type or model, e.g. "PIGA 16"
  std::string manufacturer;         // its maker
  std::string serial_number;        // its serial number
  std::string date_of_receipt;      // YYYY-MM-DD, when the item reached the laboratory
  std::string date_of_calibration;  // YYYY-MM-DD, the day of the test (of its last run)
  std::string date_of_issue;        // YYYY-MM-DD, not before the calibration
  std::string place;                // where it was calibrated, if not at the laboratory
  std::string conditions;           // the environment during the test, e.g. "(20 ± 1) °C, 40 % RH"
  std::string procedure;            // the laboratory's written procedure, e.g. "CP-ACC-07 rev. 3"
  std::string radius_standard;      // traceability of the arm radius: the standard and its certificate
  std::string rate_standard;        // traceability of the rate (time base, encoders) and its certificate
  std::string fixed_terms_source;   // where the fixed terms' values come from, e.g. "dividing head, CAL-2025-0077"
  std::string operator_name;        // key "operator": who performed the calibration (a signature line)
  std::string approved_by;          // who approves the certificate (a signature line)
  std::string remarks;              // anything else the certificate must say
  // [certificate.traceability]: per quantity that enters the budget, the standard it is traceable to and its
  // certificate, in the order written. The key is a kind of kTraceabilityKinds or an input id of [tolerances]
  // or [[inputs]]; radius_standard and rate_standard are the kinds "radius" and "rate".
  std::vector<std::pair<std::string, std::string>> traceability;

  bool operator==(const Certificate&) const = default;
};

// One field of the table: its key in the configuration, its label on the certificate, the member it sets,
// and whether it is a date. The reader, the certificate page and the docs all list the fields from here.
struct CertificateField {
  std::string_view key;
  std::string_view label;
  std::string Certificate::*member;
  bool date = false;
};

inline const std::array<CertificateField, 21> kCertificateFields{{
    {"number", "Certificate number", &Certificate::number},
    {"revision", "Revision", &Certificate::revision},
    {"replaces", "Replaces certificate", &Certificate::replaces},
    {"laboratory", "Calibration laboratory", &Certificate::laboratory},
    {"accreditation", "Accreditation", &Certificate::accreditation},
    {"customer", "Customer", &Certificate::customer},
    {"instrument", "Item calibrated", &Certificate::instrument},
    {"manufacturer", "Manufacturer", &Certificate::manufacturer},
    {"serial_number", "Serial number", &Certificate::serial_number},
    {"date_of_receipt", "Date of receipt", &Certificate::date_of_receipt, true},
    {"date_of_calibration", "Date of calibration", &Certificate::date_of_calibration, true},
    {"date_of_issue", "Date of issue", &Certificate::date_of_issue, true},
    {"place", "Place of calibration", &Certificate::place},
    {"conditions", "Ambient conditions", &Certificate::conditions},
    {"procedure", "Calibration procedure", &Certificate::procedure},
    {"radius_standard", "Traceability of the radius", &Certificate::radius_standard},
    {"rate_standard", "Traceability of the rate", &Certificate::rate_standard},
    {"fixed_terms_source", "Source of the fixed terms", &Certificate::fixed_terms_source},
    {"operator", "Calibrated by", &Certificate::operator_name},
    {"approved_by", "Approved by", &Certificate::approved_by},
    {"remarks", "Remarks", &Certificate::remarks},
}};

// The kinds of quantity a [certificate.traceability] key may name besides an input id: its key and what the
// certificate calls it.
struct TraceabilityKind {
  std::string_view key;
  std::string_view label;
};
inline constexpr std::array<TraceabilityKind, 9> kTraceabilityKinds{{
    {"radius", "arm radius"},
    {"length", "lengths of the machine (runouts, floats, offsets)"},
    {"angle", "angles of the axes and of the mounting"},
    {"rate", "rotation rate (encoders)"},
    {"time_base", "time base"},
    {"g", "local gravity g"},
    {"output", "output measuring chain"},
    {"fixed_terms", "fixed terms of the model"},
    {"temperature", "temperature"},
}};
// What the certificate calls a traceability key: its kind's label, else the key itself (an input id, whose
// name the budget gives).
std::string_view traceability_label(std::string_view key);

// An input of the budget and the kind of standard it is traceable to (InputDescription::traceability).
struct TracedInput {
  std::string id;
  std::string kind;
};
// One line of the certificate's traceability: a key of [certificate.traceability] (a kind or an input id), the
// standard stated for it ("" when none is), and the budget's inputs that rest on it.
struct TraceabilityLine {
  std::string key;
  std::string standard;
  std::vector<std::string> inputs;
};
// The traceability of a budget's inputs: the lines stated, in the order written (radius_standard and
// rate_standard first, as the kinds radius and rate; fixed_terms_source as the kind fixed_terms), then a line
// with no standard for each kind the inputs need that none states. An input rests on the line of its own id
// when one is stated, else on its kind's.
std::vector<TraceabilityLine> traceability_lines(const Certificate& certificate,
                                                 const std::vector<TracedInput>& inputs);
// The lines of traceability_lines without a standard, as a warning for the laboratory: the kinds and the
// inputs that rest on them, and the keys that would state them; "" when every input is traceable.
std::string traceability_gaps_text(const std::vector<TraceabilityLine>& lines);

// Why `text` is no calendar date YYYY-MM-DD (a real day of the Gregorian calendar, year 1900…9999), or empty
// when it is one.
std::string calendar_date_problem(std::string_view text);

}  // namespace ccal

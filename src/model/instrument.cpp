#include "ccal/model/instrument.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <numbers>

namespace ccal {

namespace {
struct NamedTerm {
  std::string_view id;
  TermKind kind;
};
constexpr std::array<NamedTerm, 9> kNamedTerms{{{"K_oq", TermKind::abs_square},
                                                {"K_p", TermKind::p},
                                                {"K_o", TermKind::o},
                                                {"K_ip", TermKind::ip},
                                                {"K_io", TermKind::io},
                                                {"K_pp", TermKind::pp},
                                                {"K_oo", TermKind::oo},
                                                {"K_po", TermKind::po},
                                                {"K_w", TermKind::rate}}};
}  // namespace

std::optional<TermSpec> parse_term(std::string_view id) {
  for (const auto& t : kNamedTerms)
    if (t.id == id) return TermSpec{t.kind, 0};
  if (id.size() < 2 || id[0] != 'K') return std::nullopt;
  int n = -1;
  const auto [end, ec] = std::from_chars(id.data() + 1, id.data() + id.size(), n);
  if (ec != std::errc{} || end != id.data() + id.size() || n < 0 || n > kMaxPower) return std::nullopt;
  if (id.size() > 2 && id[1] == '0') return std::nullopt;  // "K01" is not an id
  return TermSpec{TermKind::power, n};
}

std::string term_id(const TermSpec& term) {
  if (term.kind == TermKind::power) {
    std::string id(1, 'K');  // built in two steps: GCC 12 warns falsely (-Wrestrict) on "K" + std::string
    id += std::to_string(term.power);
    return id;
  }
  for (const auto& t : kNamedTerms)
    if (t.kind == term.kind) return std::string(t.id);
  return "?";
}

std::vector<std::string> all_term_ids() {
  std::vector<std::string> ids;
  for (int n = 0; n <= kMaxPower; ++n) ids.push_back(term_id({TermKind::power, n}));
  for (const auto& t : kNamedTerms) ids.emplace_back(t.id);
  return ids;
}

int term_rank(const TermSpec& term) {
  if (term.kind == TermKind::power) return term.power;
  for (std::size_t k = 0; k < kNamedTerms.size(); ++k)
    if (kNamedTerms[k].kind == term.kind) return kMaxPower + 1 + static_cast<int>(k);
  return kMaxPower + 1 + static_cast<int>(kNamedTerms.size());
}

std::vector<TermSpec> InstrumentModel::terms() const {
  std::vector<TermSpec> out;
  out.reserve(term_ids.size());
  for (const auto& id : term_ids) out.push_back(parse_term(id).value());
  return out;
}

std::optional<double> InstrumentModel::coefficient(std::string_view id) const {
  for (std::size_t k = 0; k < term_ids.size(); ++k)
    if (term_ids[k] == id) return coefficients[Eigen::Index(k)];
  return std::nullopt;
}

InstrumentModel paper_piga() {
  constexpr double deg = std::numbers::pi / 180.0;
  InstrumentModel m;
  m.name = "PIGA (Wang & Ren 2014)";
  m.output_unit = "deg/s";
  m.term_ids = {"K0", "K1", "K2", "K3"};
  m.coefficients = Eigen::Vector4d(0.061973, 505.2097, 0.02, 0.003) * deg;
  m.rate_gain = 1.0;
  return m;
}

std::string coefficient_unit(std::string_view output_unit, const TermSpec& term, std::string_view g) {
  if (output_unit.empty()) return "";
  const std::string out(output_unit);
  switch (term.kind) {
    case TermKind::power:
      if (term.power == 0) return out;
      if (term.power == 1) return fmt::format("{}/{}", out, g);
      return fmt::format("{}/{}^{}", out, g, term.power);
    case TermKind::p:
    case TermKind::o:
      return fmt::format("{}/{}", out, g);
    case TermKind::rate:
      return out + "/(rad/s)";
    default:
      return fmt::format("{}/{}^2", out, g);
  }
}

std::string coefficient_unit(std::string_view output_unit, std::string_view term_id, std::string_view g) {
  return coefficient_unit(output_unit, parse_term(term_id).value(), g);
}

}  // namespace ccal

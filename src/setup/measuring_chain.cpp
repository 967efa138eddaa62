#include "ccal/setup/measuring_chain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "ccal/model/error_sources.hpp"
#include "ccal/model/instrument.hpp"

namespace ccal {

namespace {

constexpr int kEncoderHarmonics = kMaxHarmonicOrder + 1;

// The fixed ids of the chain and what they are.
struct NamedInput {
  ChainKind kind;
  std::string_view id, name;
};
constexpr NamedInput kNamedInputs[] = {
    {ChainKind::gravity, "g", "local gravity (the g of the g-levels and of the coefficients)"},
    {ChainKind::time_base, "time_base", "time base of the logs (relative frequency error of their clock)"},
    {ChainKind::output_gain, "output_gain", "gain of the output's reading (relative)"},
    {ChainKind::output_offset, "output_offset", "offset of the output's reading"},
};

int term_position(std::string_view id) {
  const std::vector<std::string> ids = all_term_ids();
  const auto it = std::find(ids.begin(), ids.end(), id);
  return it == ids.end() ? -1 : int(it - ids.begin());
}

// "encoder1_c2" → {1, 2, cos}; nullopt for anything else.
std::optional<EncoderTerm> parse_encoder_id(std::string_view id) {
  EncoderTerm t;
  if (id.starts_with("encoder1_"))
    t.drive = 1;
  else if (id.starts_with("encoder3_"))
    t.drive = 3;
  else
    return std::nullopt;
  id.remove_prefix(9);
  if (id.size() < 2 || (id[0] != 'c' && id[0] != 's')) return std::nullopt;
  t.is_sine = id[0] == 's';
  const auto [end, ec] = std::from_chars(id.data() + 1, id.data() + id.size(), t.harmonic);
  if (ec != std::errc{} || end != id.data() + id.size() || t.harmonic < 1 || t.harmonic > kMaxHarmonicOrder)
    return std::nullopt;
  return t;
}

}  // namespace

int chain_parameter(ChainInput input) {
  return kChainParameterBase + int(input.kind) * kChainKindStride + input.index;
}

bool is_chain_parameter(int parameter) noexcept { return parameter >= kChainParameterBase; }

ChainInput chain_input(int parameter) {
  if (!is_chain_parameter(parameter))
    throw std::invalid_argument(fmt::format("parameter code {} is no input of the measuring chain", parameter));
  const int offset = parameter - kChainParameterBase;
  return {ChainKind(offset / kChainKindStride), offset % kChainKindStride};
}

int encoder_index(EncoderTerm term) {
  return ((term.drive == 3 ? 1 : 0) * 2 + (term.is_sine ? 1 : 0)) * kEncoderHarmonics + term.harmonic;
}

EncoderTerm encoder_term(int index) {
  const int pair = index / kEncoderHarmonics;
  return {pair / 2 == 1 ? 3 : 1, index % kEncoderHarmonics, pair % 2 == 1};
}

double MeasuringChain::error(int parameter) const {
  for (const auto& [p, value] : errors)
    if (p == parameter) return value;
  return 0.0;
}

std::string chain_input_id(int parameter, const MeasuringChain& chain) {
  const ChainInput in = chain_input(parameter);
  for (const NamedInput& n : kNamedInputs)
    if (n.kind == in.kind) return std::string(n.id);
  if (in.kind == ChainKind::fixed_term) return all_term_ids().at(std::size_t(in.index));
  if (in.kind == ChainKind::encoder) {
    const EncoderTerm t = encoder_term(in.index);
    return fmt::format("encoder{}_{}{}", t.drive, t.is_sine ? 's' : 'c', t.harmonic);
  }
  return chain.declared.at(std::size_t(in.index)).id;
}

std::string chain_input_name(int parameter, const MeasuringChain& chain) {
  const ChainInput in = chain_input(parameter);
  for (const NamedInput& n : kNamedInputs)
    if (n.kind == in.kind) return std::string(n.name);
  if (in.kind == ChainKind::fixed_term)
    return fmt::format("fixed term {} (its value from another calibration)", all_term_ids().at(std::size_t(in.index)));
  if (in.kind == ChainKind::encoder) {
    const EncoderTerm t = encoder_term(in.index);
    return fmt::format("{} encoder's angle error, {} {} per revolution", t.drive == 1 ? "main-axis" : "platform",
                       t.is_sine ? "sin" : "cos", t.harmonic);
  }
  const DeclaredInput& d = chain.declared.at(std::size_t(in.index));
  return d.description.empty() ? d.id : d.description;
}

std::optional<int> find_chain_input(std::string_view id, const MeasuringChain& chain,
                                    const std::vector<std::string>& fixed_terms, int harmonic_order) {
  for (const NamedInput& n : kNamedInputs)
    if (n.id == id) return chain_parameter({n.kind, 0});
  if (std::find(fixed_terms.begin(), fixed_terms.end(), id) != fixed_terms.end())
    return chain_parameter({ChainKind::fixed_term, term_position(id)});
  if (const auto t = parse_encoder_id(id); t && t->harmonic <= harmonic_order)
    return chain_parameter({ChainKind::encoder, encoder_index(*t)});
  for (std::size_t i = 0; i < chain.declared.size(); ++i)
    if (chain.declared[i].id == id) return chain_parameter({ChainKind::declared, int(i)});
  return std::nullopt;
}

std::vector<std::string> chain_input_ids(const MeasuringChain& chain, const std::vector<std::string>& fixed_terms) {
  std::vector<std::string> out;
  for (const NamedInput& n : kNamedInputs) out.emplace_back(n.id);
  out.insert(out.end(), fixed_terms.begin(), fixed_terms.end());
  for (const DeclaredInput& d : chain.declared) out.push_back(d.id);
  return out;
}

std::string chain_input_ids_text(const MeasuringChain& chain, const std::vector<std::string>& fixed_terms) {
  std::string out;
  for (const std::string& id : chain_input_ids(chain, fixed_terms)) out += (out.empty() ? "" : ", ") + id;
  return out + ", encoder1_c<k>, encoder1_s<k>, encoder3_c<k>, encoder3_s<k>";
}

}  // namespace ccal

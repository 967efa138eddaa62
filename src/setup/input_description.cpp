#include "ccal/setup/input_description.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ccal {

namespace {

struct UnitFacts {
  Dimension dim;
  std::string_view display, example;
};

UnitFacts layout_unit_facts(SourceUnit u) {
  switch (u) {
    case SourceUnit::rad:
      return {kind::angle, "rad", "1e-5 rad"};
    case SourceUnit::m:
      return {kind::length, "um", "25 um"};
    case SourceUnit::rad_per_s:
      return {kind::angular_rate, "rad/s", "0.5e-6 rad/s"};
    case SourceUnit::m_per_rad_per_s_squared:
      return {kind::length / pow(kind::angular_rate, 2), "m/(rad/s)^2", "8.5e-8 m/(rad/s)^2"};
    case SourceUnit::relative:
      return {kind::dimensionless, "ppm", "10 ppm"};
  }
  return {kind::dimensionless, "ppm", "10 ppm"};
}

std::string si_symbol(Dimension dim) {
  const std::string s = si_unit(dim);
  return s.empty() ? "1" : s;
}

// The kind of standard a chain input is traceable to (kTraceabilityKinds).
std::string chain_traceability(ChainKind kind) {
  switch (kind) {
    case ChainKind::gravity:
      return "g";
    case ChainKind::time_base:
      return "time_base";
    case ChainKind::output_gain:
    case ChainKind::output_offset:
      return "output";
    case ChainKind::fixed_term:
      return "fixed_terms";
    case ChainKind::encoder:
      return "rate";
    case ChainKind::declared:
      break;
  }
  return "";
}

}  // namespace

Dimension output_dimension(const std::string& output_unit) {
  return parse_unit(pulse_as_rad(output_unit)).dim;
}

InputDescription describe_layout_parameter(const ErrorLayout& layout, int parameter) {
  if (parameter < 0 || parameter >= layout.size())
    throw std::invalid_argument(fmt::format("parameter {} is outside the layout (0…{})", parameter, layout.size() - 1));
  InputDescription d;
  d.id = layout.parameter_id(parameter);
  d.name = layout.parameter_name(parameter);
  const UnitFacts f = layout_unit_facts(layout.parameter_unit(parameter));
  d.dim = f.dim;
  d.si_unit = std::string(unit_symbol(layout.parameter_unit(parameter)));
  d.display_unit = std::string(f.display);
  d.example = std::string(f.example);
  switch (layout.parameter_unit(parameter)) {
    case SourceUnit::m:  // the radius's static error and its stretch, or a runout, float or offset
      d.traceability = d.id.starts_with("dR") ? "radius" : "length";
      break;
    case SourceUnit::m_per_rad_per_s_squared:
      d.traceability = "radius";
      break;
    case SourceUnit::rad:
      d.traceability = "angle";
      break;
    case SourceUnit::rad_per_s:
    case SourceUnit::relative:  // a rate ripple, relative to the rate
      d.traceability = "rate";
      break;
  }
  return d;
}

InputDescription describe_input(const Config& config, int parameter) {
  if (!is_chain_parameter(parameter)) {
    InputDescription d = describe_layout_parameter(config.centrifuge.layout, parameter);
    d.estimate_si = config.centrifuge.errors[parameter];
    return d;
  }
  InputDescription d;
  d.id = chain_input_id(parameter, config.chain);
  d.name = chain_input_name(parameter, config.chain);
  const ChainInput in = chain_input(parameter);
  const std::string& output = config.instrument.output_unit;
  d.traceability = chain_traceability(in.kind);
  switch (in.kind) {
    case ChainKind::gravity:
      d.dim = kind::acceleration;
      d.display_unit = "m/s^2";
      d.example = "0.001 m/s^2";
      break;
    case ChainKind::time_base:
    case ChainKind::output_gain:
      d.dim = kind::dimensionless;
      d.display_unit = "ppm";
      d.example = "1 ppm";
      break;
    case ChainKind::output_offset:
      d.dim = output_dimension(output);
      d.display_unit = output;
      d.example = fmt::format("1e-4 {}", output);
      break;
    case ChainKind::fixed_term: {
      if (const auto it = config.identification.fixed_terms.find(d.id); it != config.identification.fixed_terms.end())
        d.relative_to = std::abs(it->second);
      d.display_unit = coefficient_unit(output, d.id, config.instrument.g_symbol);
      d.dim = parse_unit(pulse_as_rad(d.display_unit)).dim;
      d.example = fmt::format("1e-4 {}", d.display_unit);
      break;
    }
    case ChainKind::encoder:
      d.dim = kind::angle;
      d.display_unit = "arcsec";
      d.example = "0.5 arcsec";
      break;
    case ChainKind::declared: {
      const DeclaredInput& in_decl = config.chain.declared.at(std::size_t(in.index));
      d.dim = kind::dimensionless;
      d.display_unit = in_decl.unit;
      d.si_unit = in_decl.unit;
      d.example = fmt::format("0.05 (in {})", in_decl.unit);
      d.own_unit = true;
      d.traceability = d.id;
      return d;
    }
  }
  d.si_unit = si_symbol(d.dim);
  return d;
}

double unit_in_si(const InputDescription& d, const std::string& unit) {
  if (d.own_unit) return 1.0;
  const Quantity q = parse_unit(pulse_as_rad(unit));
  if (d.relative_to > 0 && q.dim == kind::dimensionless && !(d.dim == kind::dimensionless))
    return q.value_si * d.relative_to;
  return q.value_si;
}

std::string input_quantity_text(const InputDescription& d, double si, const std::string& unit) {
  const std::string number = fmt::format("{:.4g}", si / unit_in_si(d, unit));
  return unit.empty() ? number : fmt::format("{} {}", number, unit);
}

}  // namespace ccal

// Figures and units as the certificate writes them (certificate_parts.hpp).
#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "certificate_parts.hpp"

namespace ccal::render::certificate_parts {
namespace {

constexpr const char* kSuperscripts[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};

// An exponent's text (digits and an optional sign) as superscripts.
std::string superscript(std::string_view digits) {
  std::string out;
  // an exponent's leading zeros dropped ("-05" → ⁻⁵), one digit kept
  std::string kept;
  for (const char c : digits)
    if (c != '0' || (!kept.empty() && kept.back() >= '0' && kept.back() <= '9')) kept += c;
  if (kept.empty() || !(kept.back() >= '0' && kept.back() <= '9')) kept += '0';
  for (const char c : kept) {
    if (c == '-')
      out += "⁻";
    else if (c == '+')
      continue;
    else if (c >= '0' && c <= '9')
      out += kSuperscripts[c - '0'];
  }
  return out;
}

std::string minus_sign(std::string text) {
  if (!text.empty() && text.front() == '-') text.replace(0, 1, "−");
  return text;
}

}  // namespace

std::string unit_html(std::string_view unit) {
  std::string out;
  for (std::size_t i = 0; i < unit.size();) {
    const char c = unit[i];
    if (std::isalpha(static_cast<unsigned char>(c))) {
      std::size_t end = i;
      while (end < unit.size() && std::isalpha(static_cast<unsigned char>(unit[end]))) ++end;
      const std::string_view word = unit.substr(i, end - i);
      out += word == "deg"      ? "°"
             : word == "um"     ? "µm"
             : word == "arcsec" ? "″"
             : word == "rtHz"   ? "√Hz"
             : word == "gn"     ? "g<sub>n</sub>"
                                : report_html::escape(word);
      i = end;
    } else if (c == '^') {
      std::size_t end = i + 1;
      while (end < unit.size() && (unit[end] == '-' || std::isdigit(static_cast<unsigned char>(unit[end]))))
        ++end;
      out += superscript(unit.substr(i + 1, end - i - 1));
      i = end;
    } else {
      out += report_html::escape(std::string_view(&unit[i], 1));
      ++i;
    }
  }
  return out;
}

std::string words_html(std::string_view text) {
  static constexpr std::pair<std::string_view, std::string_view> kGreek[] = {
      {"alpha", "α"}, {"beta", "β"},  {"gamma", "γ"}, {"theta", "θ"}, {"phi", "φ"},
      {"psi", "ψ"},   {"omega", "ω"}, {"Omega", "Ω"}, {"Delta", "Δ"}};
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isalpha(static_cast<unsigned char>(c))) {
      std::size_t end = i;
      while (end < text.size() && std::isalpha(static_cast<unsigned char>(text[end]))) ++end;
      const std::string_view word = text.substr(i, end - i);
      std::string shown = report_html::escape(word);
      for (const auto& [name, letter] : kGreek)
        if (word == name) shown = letter;
      out += shown;
      i = end;
    } else if (c == '^') {
      std::size_t end = i + 1;
      while (end < text.size() && (text[end] == '-' || std::isdigit(static_cast<unsigned char>(text[end]))))
        ++end;
      out += superscript(text.substr(i + 1, end - i - 1));
      i = end;
    } else {
      out += c == '*' ? std::string("·") : report_html::escape(std::string_view(&text[i], 1));
      ++i;
    }
  }
  return out;
}

std::string number_html(double value, int digits) {
  if (value == 0) return "0";
  const std::string plain = fmt::format("{:.{}g}", value, digits);
  if (plain.find('e') == std::string::npos && std::abs(value) >= 1e-4)
    return "<span class=\"nowrap\">" + minus_sign(plain) + "</span>";
  // m × 10ⁿ: the mantissa from %e, its exponent as superscripts
  const std::string e = fmt::format("{:.{}e}", value, digits - 1);
  const std::size_t at = e.find('e');
  std::string mantissa = e.substr(0, at);
  return "<span class=\"nowrap\">" + minus_sign(mantissa) + " × 10" + superscript(e.substr(at + 1)) +
         "</span>";
}

std::string dof_text(const Json& dof) {
  if (dof.is_null()) return "∞";
  const double v = dof.get<double>();
  return std::isfinite(v) ? fmt::format("{:.0f}", std::floor(v)) : "∞";
}

std::string coverage_factor_text(double k) { return fmt::format("{:.2f}", k); }

std::string method_html(const Json& coefficient) {
  if (coefficient["interval_method"] == "monte_carlo") return "Monte Carlo (JCGM 101)";
  const Json& dof = coefficient["effective_dof"];
  if (coefficient["interval_method"] == "coverage_factor") {
    // A stated k: the distribution it is read in, and at finite ν_eff the coverage it then gives (below the
    // normal one the paragraph states).
    if (dof.is_null()) return "stated k, normal (ν<sub>eff</sub> = ∞)";
    const Json& p = coefficient["stated_coverage_probability"]["student_t"];
    return "stated k, Student's t at ν<sub>eff</sub> = " + dof_text(dof) +
           (p.is_number() ? ", coverage probability " + approximate_percent_text(p.get<double>()) : "");
  }
  if (dof.is_null()) return "normal (ν<sub>eff</sub> = ∞)";
  return "Student's t at ν<sub>eff</sub> = " + dof_text(dof);
}

std::string term_html(std::string_view id) {
  if (id.size() < 2 || id[0] != 'K') return report_html::escape(id);
  const std::string_view rest = id.substr(id[1] == '_' ? 2 : 1);
  return "K<sub>" + report_html::escape(rest) + "</sub>";
}

std::string percent_text(double p) { return fmt::format("{:g} %", 100 * p); }

// EA-4/02's "approximately 95 %" for k = 2: two significant digits, three from 99 % on (99.7 % for k = 3).
std::string approximate_percent_text(double p) {
  return fmt::format("{:.{}g} %", 100 * p, p < 0.99 ? 2 : 3);
}

std::string base_name(std::string_view path) {
  const std::size_t slash = path.find_last_of('/');
  return std::string(slash == std::string_view::npos ? path : path.substr(slash + 1));
}

}  // namespace ccal::render::certificate_parts

#include "report_html.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"

namespace ccal::render::report_html {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  return out;
}

std::string script_json(const Json& value) {
  const std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

namespace {
double value_at(const Doc& doc, const std::string& pointer) {
  const Json::json_pointer p(pointer);
  if (!doc.json.contains(p) || !doc.json.at(p).is_number())
    throw std::logic_error(fmt::format("report: {}:{} is not a number of that output", doc.name, pointer));
  return doc.json.at(p).get<double>();
}

std::string attributes(const Doc& doc, const std::string& pointer, int digits, double scale) {
  return fmt::format("data-src=\"{}:{}\" data-digits=\"{}\"{}", escape(doc.name), escape(pointer), digits,
                     scale == 1.0 ? std::string() : fmt::format(" data-scale=\"{:.17g}\"", scale));
}
}  // namespace

std::string num_cell(const Doc& doc, const std::string& pointer, int digits, double scale) {
  return fmt::format("<td class=\"num\" {}>{:.{}g}</td>", attributes(doc, pointer, digits, scale),
                     value_at(doc, pointer) * scale, digits);
}

std::string num_span(const Doc& doc, const std::string& pointer, int digits, double scale) {
  return fmt::format("<span class=\"num\" {}>{:.{}g}</span>", attributes(doc, pointer, digits, scale),
                     value_at(doc, pointer) * scale, digits);
}

std::string num_cell_or_zero(const Doc& doc, const std::string& pointer, const std::string& zero_if,
                             int digits, double scale) {
  const Json::json_pointer flag(zero_if);
  if (!doc.json.contains(flag) || !doc.json.at(flag).is_boolean())
    throw std::logic_error(fmt::format("report: {}:{} is not a flag of that output", doc.name, zero_if));
  const double value = value_at(doc, pointer) * scale;
  return fmt::format(
      "<td class=\"num\" {} data-round-off=\"{}:{}\">{}</td>", attributes(doc, pointer, digits, scale),
      escape(doc.name), escape(zero_if),
      doc.json.at(flag).get<bool>() ? std::string("0") : fmt::format("{:.{}g}", value, digits));
}

std::string ratio_cell(const Doc& doc, const std::string& numerator, const std::string& denominator,
                       int digits) {
  const double value = value_at(doc, numerator) / value_at(doc, denominator);
  return fmt::format("<td class=\"num\" data-ratio=\"{}:{} {}\" data-digits=\"{}\">{:.{}g}</td>",
                     escape(doc.name), escape(numerator), escape(denominator), digits, value, digits);
}

namespace {

// A string of the output in an element that names its place (the check compares it character for character).
std::string text_element(std::string_view tag, const Doc& doc, const std::string& pointer) {
  return fmt::format("<{0} class=\"num\" data-text=\"{1}:{2}\">{3}</{0}>", tag, escape(doc.name), escape(pointer),
                     escape(doc.json.at(Json::json_pointer(pointer)).get<std::string>()));
}

}  // namespace

std::string text_num_cell(const Doc& doc, const std::string& pointer) { return text_element("td", doc, pointer); }

std::string text_num_span(const Doc& doc, const std::string& pointer) { return text_element("span", doc, pointer); }

std::string text_cell(std::string_view text) { return "<td>" + escape(text) + "</td>"; }

std::string chart(const std::string& id, const Json& spec) {
  return fmt::format(
      "<div class=\"chart\" id=\"{0}\"></div>\n<script type=\"application/json\" class=\"vl-spec\" "
      "data-target=\"{0}\">{1}</script>\n",
      escape(id), script_json(spec));
}

std::string css_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\' || c == '<' || c == '>' || c == '\n' || c == '\r' || c == '&')
      out += fmt::format("\\{:x} ", static_cast<unsigned char>(c));
    else
      out += c;
  }
  return out + "\"";
}

}  // namespace ccal::render::report_html

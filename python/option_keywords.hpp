#pragma once
// A verb's options as Python keywords, from the verb's options table (core/options.hpp): the keyword is the
// field's name, its default the options struct's, its value read by the library's parsers (integers as the
// command line reads them, so that 1e5 is a whole number and -5 is refused with the same words), and the
// range checked by the verb itself. So Python refuses what the command line refuses, worded with the keyword.
//
// A verb binds its keywords in one line each way:
//   m.def("monte_carlo", [](const Config& cfg, const py::object& progress, const py::kwargs& keywords) {
//           auto o = options_from_keywords<verbs::MonteCarloOptions>(keywords, "monte_carlo");
//           ...
//         }, py::arg("config"), py::kw_only(), py::arg("progress") = py::none(), doc);
//   record_keywords<verbs::MonteCarloOptions>(m, "monte_carlo");
// record_keywords lists, in the module's `_option_keywords`, each keyword with its default, type and help;
// python/ccal/_signatures.py makes them the function's keyword-only parameters (inspect.signature, help(),
// the stubs). Fields that a binding converts itself (a dict of targets) are named in `skip`.

#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "ccal/core/options.hpp"

namespace ccal::python {

namespace py = pybind11;

namespace keywords {

// TypeError "<function>() got an unexpected keyword argument 'x'; did you mean 'y'? accepted: ...", the
// accepted names being the binding's own arguments, then the options'.
[[noreturn]] void unknown_keyword(std::string_view function, std::string_view keyword,
                                  std::initializer_list<std::string_view> own,
                                  const std::vector<std::string_view>& accepted);
// TypeError "<field>: expected <expected>, got <type> (<repr>)".
[[noreturn]] void wrong_type(std::string_view field, std::string_view expected, py::handle value);
// A datetime.date that is not a datetime (whose isoformat() has the time too).
bool is_calendar_date(py::handle value);
// A Python int or float (also NumPy's), not a bool or a str.
bool is_number(py::handle value);
// The value as the command line would have read its text: an int's digits, a float's shortest repr.
std::string number_text(py::handle value);
std::vector<std::string> strings(std::string_view field, py::handle value);
std::vector<double> reals(std::string_view field, py::handle value);

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

// A number of type Number from a Python value, by the library's parsers.
template <class Number>
Number number(std::string_view field, py::handle value, const OptionRange& range = {}) {
  if (!is_number(value))
    wrong_type(field, std::is_floating_point_v<Number> ? "a number" : "an integer", value);
  const std::string text = number_text(value);
  if constexpr (std::is_floating_point_v<Number>)
    return Number(parse_real_option(field, text, range));
  else if constexpr (std::is_unsigned_v<Number>)
    return Number(parse_unsigned_option(field, text, range));
  else
    return Number(parse_integer_option(field, text, std::numeric_limits<Number>::min(),
                                       std::numeric_limits<Number>::max(), range));
}

// Sets `field` (the member's value) from a Python value.
template <class Field>
void assign(Field& field, std::string_view name, py::handle value, const OptionRange& range = {}) {
  if constexpr (is_optional<Field>::value) {
    if (value.is_none()) {
      field.reset();
    } else {
      typename Field::value_type inner{};
      assign(inner, name, value, range);
      field = inner;
    }
  } else if constexpr (std::is_same_v<Field, bool>) {
    if (!py::isinstance<py::bool_>(value)) wrong_type(name, "True or False", value);
    field = value.cast<bool>();
  } else if constexpr (std::is_same_v<Field, std::string>) {
    // A date (history's date, at) also as Python's datetime.date, written YYYY-MM-DD by its isoformat().
    if ((name == "date" || name == "at") && is_calendar_date(value)) {
      field = value.attr("isoformat")().cast<std::string>();
      return;
    }
    if (!py::isinstance<py::str>(value)) wrong_type(name, "a str", value);
    field = value.cast<std::string>();
  } else if constexpr (std::is_same_v<Field, std::vector<std::string>>) {
    field = strings(name, value);
  } else if constexpr (std::is_same_v<Field, std::vector<double>>) {
    field = reals(name, value);
  } else {
    field = number<Field>(name, value, range);
  }
}

// The Python value of a field (its default) and the name of its type in a signature.
template <class Field>
py::object python_value(const Field& field) {
  if constexpr (is_optional<Field>::value)
    return field ? python_value(*field) : py::none();
  else
    return py::cast(field);
}

template <class Field>
std::string type_name() {
  if constexpr (is_optional<Field>::value)
    return "Optional[" + type_name<typename Field::value_type>() + "]";
  else if constexpr (std::is_same_v<Field, bool>)
    return "bool";
  else if constexpr (std::is_same_v<Field, std::string>)
    return "str";
  else if constexpr (std::is_same_v<Field, std::vector<std::string>>)
    return "List[str]";
  else if constexpr (std::is_same_v<Field, std::vector<double>>)
    return "List[float]";
  else if constexpr (std::is_floating_point_v<Field>)
    return "float";
  else
    return "int";
}

// What a row accepts, for the docstring: its range, or the names of an enumeration's values.
template <class Options, class Member>
std::string accepted_text(const OptionSpec<Options>& row, const Member& member) {
  if constexpr (std::is_same_v<Member, OptionEnum<Options>>) {
    std::string names;
    for (std::string_view n : member.names) names += (names.empty() ? "'" : ", '") + std::string(n) + "'";
    return names;
  } else {
    using Field = typename Member::type;
    if constexpr (std::is_same_v<Field, bool> || std::is_same_v<Field, std::string> ||
                  std::is_same_v<Field, std::vector<std::string>> ||
                  std::is_same_v<Field, std::optional<std::vector<std::string>>>)
      return "";
    else if (row.range.low <= -1e308 && row.range.high >= 1e308 && !row.range.also)
      return "";  // no range but the type's (an unsigned seed)
    else
      return row.range.text();
  }
}

bool skipped(std::string_view field, std::initializer_list<std::string_view> skip);
// Adds (name, default, type, help) to the module's _option_keywords[function].
void record(py::module_& m, std::string_view function, std::string_view name, py::object default_value,
            const std::string& type, const std::string& help);

}  // namespace keywords

// The options of a verb from its Python keywords: `options` with each keyword's field set. Every keyword must
// be a row of the table not in `skip` (fields the binding converts itself); a value of the wrong type is a
// TypeError, one the parser refuses an OptionError naming the field (ccal.InputError). `own`: the binding's
// own arguments, listed first among the accepted names of a mistyped keyword.
template <class Options>
Options options_from_keywords(const py::kwargs& given, std::string_view function, Options options = {},
                              std::initializer_list<std::string_view> skip = {},
                              std::initializer_list<std::string_view> own = {"config"}) {
  const OptionTable<Options> table = option_table<Options>();
  for (const auto& [key, value] : given) {
    const std::string name = py::str(key);
    const auto row = std::find_if(table.begin(), table.end(), [&](const OptionSpec<Options>& r) {
      return r.field == name && !keywords::skipped(r.field, skip);
    });
    if (row == table.end()) {
      std::vector<std::string_view> accepted;
      for (const OptionSpec<Options>& r : table)
        if (!keywords::skipped(r.field, skip)) accepted.push_back(r.field);
      keywords::unknown_keyword(function, name, own, accepted);
    }
    std::visit(
        [&](auto member) {
          if constexpr (std::is_same_v<decltype(member), OptionEnum<Options>>) {
            if (value.is_none()) return;  // unset: the configuration's
            if (!py::isinstance<py::str>(value)) keywords::wrong_type(name, "a str", value);
            member.set(options, parse_choice_option(name, value.template cast<std::string>(), member.names));
          } else if constexpr (std::is_same_v<typename decltype(member)::type, std::string>) {
            // A file's path (db=, …) may be an os.PathLike, as a path is anywhere in Python.
            const bool path = row->value_name.starts_with("FILE") || row->value_name.starts_with("DIR");
            // An empty path (an unset variable) would mean the default (the default store) or none.
            if (path && py::isinstance<py::str>(value) && value.template cast<std::string>().empty())
              throw OptionError(name, "", "the path is empty; accepted: a path, or the keyword left out");
            if (path && !py::isinstance<py::str>(value) && py::hasattr(value, "__fspath__"))
              keywords::assign(member.of(options), name, py::module_::import("os").attr("fspath")(value),
                               row->range);
            else
              keywords::assign(member.of(options), name, value, row->range);
          } else {
            keywords::assign(member.of(options), name, value, row->range);
          }
        },
        row->member);
  }
  return options;
}

// Records the keywords of `function` (its rows but `skip`) with the defaults of Options{} for its signature;
// `types`: a keyword the binding converts itself, with the Python type it takes (e.g. a number or a str).
template <class Options>
void record_keywords(py::module_& m, std::string_view function,
                     std::initializer_list<std::string_view> skip = {},
                     std::initializer_list<std::pair<std::string_view, std::string_view>> types = {}) {
  const Options defaults{};
  for (const OptionSpec<Options>& row : option_table<Options>()) {
    if (keywords::skipped(row.field, skip)) continue;
    std::visit(
        [&](auto member) {
          std::string accepted = keywords::accepted_text(row, member);
          // What None stands for, said of an optional field only (a plain seed's row states its unset value too).
          bool optional = false;
          if constexpr (!std::is_same_v<decltype(member), OptionEnum<Options>>)
            optional = keywords::is_optional<typename decltype(member)::type>::value;
          const std::string unset = row.range.unset_text.empty() || !optional
                                        ? ""
                                        : " (None: " + std::string(row.range.unset_text) + ")";
          const std::string help =
              option_help(row.help, row.range) + unset + (accepted.empty() ? "" : "; accepted: " + accepted);
          if constexpr (std::is_same_v<decltype(member), OptionEnum<Options>>) {
            const auto index = member.get(defaults);
            keywords::record(m, function, row.field,
                             index ? py::object(py::str(std::string(member.names[*index]))) : py::none(),
                             index ? "str" : "Optional[str]", help);
          } else {
            using Field = typename decltype(member)::type;
            std::string type = keywords::type_name<Field>();
            for (const auto& [field, given] : types)
              if (field == row.field) type = given;
            keywords::record(m, function, row.field, keywords::python_value(member.of(defaults)), type, help);
          }
        },
        row.member);
  }
}

}  // namespace ccal::python

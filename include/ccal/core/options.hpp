#pragma once
// The options of a library call, described once, as data.
//
// Each verb's options struct (verbs/*.hpp) has a table of its fields, `OptionTable<Options>`: per field its
// name, its member, the accepted values and a line of help. That table is the one home of an option:
//   - the verb checks its options against it (check_options; an OptionError names the field),
//   - the command line declares its flags from it (the flag is the field's name with '-' for '_':
//     coverage_probability → --coverage-probability; apps/ccal/option_flags.cpp), with the struct's default,
//   - Python takes the same names as keywords and the struct's defaults (python/),
// and each front end words an OptionError with its own spelling of the field, so the same value gets the same
// refusal everywhere. A new option is a field of the struct and one row of its table.

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/model_mode.hpp"

namespace ccal {

// An option of a library call that is not accepted. field(): the option's name in the library (the field of
// the verb's options struct, e.g. "coverage_probability"); value(): the value as given; problem(): what is
// wrong with it and what would be accepted. what() is "<field>: <value> <problem>"; a front end rewords it
// with its own name of each option (worded: the command line's flags, --coverage-probability). A problem that
// names another option of the call writes it as OptionError::name(field), so that it too is worded.
class OptionError : public InputError {
 public:
  OptionError(std::string field, std::string value, std::string problem);

  // An option named inside a problem's text: the field between two U+001F marks, worded by each front end.
  static std::string name(std::string_view field);

  const std::string& field() const noexcept { return field_; }
  const std::string& value() const noexcept { return value_; }
  const std::string& problem() const noexcept { return problem_; }
  // "<name>: <value> <problem>", or "<name>: <problem>" for an option without a value, where every option
  // is named by spelling(field) (what(): the field itself).
  std::string worded(const std::function<std::string(std::string_view field)>& spelling) const;

 private:
  std::string field_, value_, problem_;
};

// What values a numeric option accepts: [low, high] (each end open when said), finite, plus optionally one
// more value with its own meaning (e.g. 0: none). For a list, each element.
struct OptionRange {
  double low = -1e308, high = 1e308;
  bool low_open = false, high_open = false;
  std::optional<double> also;     // a value accepted besides the range
  std::string_view also_meaning;  // what it means, e.g. "none"
  std::string_view example;       // shown in the message, e.g. "2 (U = k u)"
  std::string_view note;          // a last word of the message, e.g. where a similar option is
  // What an optional field left unset stands for, as the help shows it (e.g. "all cores"): the field is optional so
  // that a value given can be told from the default.
  std::string_view unset_text;

  // [low, high]; then, by copies: open ends, one more accepted value, an example, a note.
  static constexpr OptionRange between(double low, double high) {
    OptionRange r;
    r.low = low;
    r.high = high;
    return r;
  }
  static constexpr OptionRange at_least(double low) { return between(low, 1e308); }
  constexpr OptionRange open_low() const {
    OptionRange r = *this;
    r.low_open = true;
    return r;
  }
  constexpr OptionRange open_high() const {
    OptionRange r = *this;
    r.high_open = true;
    return r;
  }
  constexpr OptionRange or_value(double value, std::string_view meaning) const {
    OptionRange r = *this;
    r.also = value;
    r.also_meaning = meaning;
    return r;
  }
  constexpr OptionRange e_g(std::string_view text) const {
    OptionRange r = *this;
    r.example = text;
    return r;
  }
  constexpr OptionRange noting(std::string_view text) const {
    OptionRange r = *this;
    r.note = text;
    return r;
  }
  constexpr OptionRange unset_means(std::string_view text) const {
    OptionRange r = *this;
    r.unset_text = text;
    return r;
  }

  bool accepts(double x) const noexcept;
  // "2 to 1000000000", "a number in (0, 1)", with the extra value, the example and the note: what a message
  // says is accepted.
  std::string text() const;
  // The interval alone, as a help line states it: "[0.5, 1)", "[1, 6]", "≥ 0", "a finite number".
  std::string interval() const;
};

// A row's help as the front ends show it: every "{range}" in it replaced by range.interval(), so that a help
// line that states the range states the row's.
std::string option_help(std::string_view help, const OptionRange& range);

// A member of an enumeration type (or an optional one), set and read through the names of its values, which
// are listed in the enumeration's order; made by enum_member<&Options::field>(names).
template <class Options>
struct OptionEnum {
  std::span<const std::string_view> names;
  void (*set)(Options&, std::size_t index) = nullptr;
  std::optional<std::size_t> (*get)(const Options&) = nullptr;  // nullopt: unset (the configuration's)
};

namespace option_detail {
// Named functions, not lambdas: their addresses are constant template arguments (lifted_rows).
template <auto Member, class Options>
void set_enum(Options& o, std::size_t index) {
  using Field = std::remove_cvref_t<decltype(o.*Member)>;
  if constexpr (requires { typename Field::value_type; })
    o.*Member = static_cast<typename Field::value_type>(index);
  else
    o.*Member = static_cast<Field>(index);
}
template <auto Member, class Options>
std::optional<std::size_t> get_enum(const Options& o) {
  using Field = std::remove_cvref_t<decltype(o.*Member)>;
  if constexpr (requires { typename Field::value_type; }) {
    if (!(o.*Member)) return std::nullopt;
    return std::size_t(*(o.*Member));
  } else {
    return std::size_t(o.*Member);
  }
}
}  // namespace option_detail

template <auto Member, class Options>
constexpr OptionEnum<Options> enum_member_of(std::span<const std::string_view> names) {
  OptionEnum<Options> e;
  e.names = names;
  e.set = &option_detail::set_enum<Member, Options>;
  e.get = &option_detail::get_enum<Member, Options>;
  return e;
}

// The class of a pointer to data member.
template <class T>
struct member_class;
template <class C, class T>
struct member_class<T C::*> {
  using type = C;
};

// enum_member<&DesignOptions::objective>(kObjectiveNames): the row member of an enumeration field.
template <auto Member>
constexpr auto enum_member(std::span<const std::string_view> names) {
  return enum_member_of<Member, typename member_class<decltype(Member)>::type>(names);
}

// A field of an options struct that an option sets: a member of the struct itself (&Options::seed) or of a
// struct it holds, reached through that member (lifted_rows below). So a verb that holds an engine's or the
// statement's options as a member has their rows in its table, each written once.
template <class Options, class T>
struct OptionField {
  using type = T;
  T Options::*direct = nullptr;
  T& (*reach)(Options&) = nullptr;  // through a held struct; null: direct

  constexpr OptionField() = default;
  constexpr OptionField(T Options::*member) : direct(member) {}
  constexpr explicit OptionField(T& (*through)(Options&)) : reach(through) {}
  T& of(Options& o) const { return reach ? reach(o) : o.*direct; }
  const T& of(const Options& o) const { return reach ? reach(const_cast<Options&>(o)) : o.*direct; }
};

// The member of an options struct that an option sets.
template <class Options>
using OptionMember =
    std::variant<OptionField<Options, bool>, OptionField<Options, int>, OptionField<Options, std::int64_t>,
                 OptionField<Options, std::uint64_t>, OptionField<Options, double>,
                 OptionField<Options, std::string>, OptionField<Options, std::vector<std::string>>,
                 OptionField<Options, std::vector<double>>,
                 OptionField<Options, std::optional<std::vector<std::string>>>,
                 OptionField<Options, std::optional<int>>, OptionField<Options, std::optional<std::int64_t>>,
                 OptionField<Options, std::optional<std::uint64_t>>, OptionField<Options, std::optional<double>>,
                 OptionEnum<Options>>;

// One option: the field's name (the front ends derive their spellings from it), the member, the accepted
// values, the name of its value in a usage line (N, p, FILE) and a line of help.
template <class Options>
struct OptionSpec {
  std::string_view field;
  OptionMember<Options> member;
  std::string_view value_name;
  std::string_view help;
  OptionRange range;
  bool required = false;  // a list that needs at least one element (an optional list: when it is set)

  constexpr OptionSpec() = default;
  constexpr OptionSpec(std::string_view field, OptionMember<Options> member, std::string_view value_name,
                       std::string_view help, OptionRange range = {}, bool required = false)
      : field(field), member(member), value_name(value_name), help(help), range(range), required(required) {}
};

template <class Options>
using OptionTable = std::span<const OptionSpec<Options>>;

// --- the rows of a held struct in its holder's table ---
//
// A verb whose options hold another struct's (ReduceOptions::statement_options, a StatementOptions) shows that
// struct's rows as its own: lifted_rows<&Holder::member, kHeldRows, first, last>() gives rows first … last − 1
// of kHeldRows (a constexpr array of OptionSpec<Held>), each field reached through the member; join_rows puts
// a table together from such pieces and the holder's own rows, in the order the help lists them.
namespace option_detail {

template <auto Outer, auto Inner>  // (o.*Outer).*Inner
auto& reach_member(typename member_class<decltype(Outer)>::type& o) {
  return (o.*Outer).*Inner;
}
template <auto Outer, auto Through>  // Through(o.*Outer): a field the held struct reaches itself
auto& reach_through(typename member_class<decltype(Outer)>::type& o) {
  return Through(o.*Outer);
}
template <auto Outer, auto Set>
void set_through(typename member_class<decltype(Outer)>::type& o, std::size_t index) {
  Set(o.*Outer, index);
}
template <auto Outer, auto Get>
std::optional<std::size_t> get_through(const typename member_class<decltype(Outer)>::type& o) {
  return Get(o.*Outer);
}

// The lifted row's member, made in one initialisation: a constant expression may not change a variant's
// active alternative by assignment (clang), so the variant is built from the alternative it holds.
template <auto Outer, const auto& Rows, std::size_t I>
constexpr OptionMember<typename member_class<decltype(Outer)>::type> lift_member() {
  using Holder = typename member_class<decltype(Outer)>::type;
  constexpr auto inner = std::get<Rows[I].member.index()>(Rows[I].member);
  using Inner = decltype(inner);
  if constexpr (requires { inner.names; }) {  // an enumeration
    OptionEnum<Holder> e;
    e.names = inner.names;
    e.set = &set_through<Outer, inner.set>;
    e.get = &get_through<Outer, inner.get>;
    return e;
  } else if constexpr (inner.reach == nullptr) {
    return OptionField<Holder, typename Inner::type>(&reach_member<Outer, inner.direct>);
  } else {
    return OptionField<Holder, typename Inner::type>(&reach_through<Outer, inner.reach>);
  }
}

template <auto Outer, const auto& Rows, std::size_t I>
constexpr auto lift_row() {
  using Holder = typename member_class<decltype(Outer)>::type;
  constexpr const auto& row = Rows[I];
  return OptionSpec<Holder>(row.field, lift_member<Outer, Rows, I>(), row.value_name, row.help, row.range,
                            row.required);
}

// Two tables one after the other, each row copied into place (not assigned, for the reason above).
template <class Options, std::size_t A, std::size_t B>
constexpr std::array<OptionSpec<Options>, A + B> join_two(const std::array<OptionSpec<Options>, A>& a,
                                                         const std::array<OptionSpec<Options>, B>& b) {
  return [&]<std::size_t... I, std::size_t... J>(std::index_sequence<I...>, std::index_sequence<J...>) {
    return std::array<OptionSpec<Options>, A + B>{a[I]..., b[J]...};
  }(std::make_index_sequence<A>{}, std::make_index_sequence<B>{});
}

}  // namespace option_detail

template <auto Outer, const auto& Rows, std::size_t First = 0, std::size_t Last = std::size(Rows)>
constexpr auto lifted_rows() {
  static_assert(First <= Last && Last <= std::size(Rows));
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array{option_detail::lift_row<Outer, Rows, First + I>()...};
  }(std::make_index_sequence<Last - First>{});
}

// The rows of the pieces, one after the other (each a std::array of OptionSpec<Options>:
// std::to_array<OptionSpec<X>>({...}) or lifted_rows).
template <class Options, std::size_t N, std::size_t... M>
constexpr auto join_rows(const std::array<OptionSpec<Options>, N>& first,
                         const std::array<OptionSpec<Options>, M>&... rest) {
  if constexpr (sizeof...(M) == 0)
    return first;
  else
    return option_detail::join_two(first, join_rows(rest...));
}

// The table of an options struct: each verb's header declares options_of(std::type_identity<Its>) and its
// source defines the rows.
template <class Options>
OptionTable<Options> option_table() {
  return options_of(std::type_identity<Options>{});
}

// The text of a number as the options show it: integers in full, others in the shortest form that reads back
// to the same double.
std::string option_number_text(double x);

// The command line's flag of a field: "--" + the field with '-' for '_' (coverage_probability →
// --coverage-probability), but for the fields whose flag takes one element of a list (targets → --target,
// logs → --log); `prefix` goes before the field (the report's allocate_ + targets → --allocate-target). The
// command line declares its flags by it, and the report writes its "same as" command lines with it.
std::string option_flag(std::string_view field, std::string_view prefix = "");

// The command-line arguments that give `options`: for every row of `table` whose value differs from its value in
// `defaults`, the flag and the value as the command line reads it back (a list one element a flag, or comma-
// separated where the flag takes the list whole; a switch alone; an enumeration by its name; numbers as
// option_value_text). So a "same as" command line names every option that is not the default.
template <class Options>
std::vector<std::string> option_arguments(const Options& options, OptionTable<Options> table,
                                          const Options& defaults = {});

// Throws OptionError for the first field of `options` that its row of `table` does not accept.
template <class Options>
void check_options(const Options& options, OptionTable<Options> table);
template <class Field, class Options>
void check_member(const Field& value, const OptionSpec<Options>& row);

// The value of an integer option written as text: digits, or any float notation of a whole number (1e5,
// 100000.0). OptionError naming `field` and echoing `text` for anything else, or a value beyond [low, high].
std::int64_t parse_integer_option(std::string_view field, std::string_view text, std::int64_t low,
                                  std::int64_t high);
std::uint64_t parse_unsigned_option(std::string_view field, std::string_view text);
// As above, but every refusal says the option's range (a bounded one) rather than the type's limits: a whole
// number beyond the type that the range refuses as well (-5 trials), as check_options says it; anything else
// (2.5, nan) as "a whole number from 2 to 1000000000".
std::uint64_t parse_unsigned_option(std::string_view field, std::string_view text, const OptionRange& range);
// As parse_integer_option, but every refusal (2.5, nan, 1e30) says the option's range rather than the type's
// limits (as the unsigned overload with a range does), unless the range is unbounded.
std::int64_t parse_integer_option(std::string_view field, std::string_view text, std::int64_t low,
                                  std::int64_t high, const OptionRange& range);
// A real option written as text (any float notation); OptionError unless it is a finite number.
double parse_real_option(std::string_view field, std::string_view text);
// As above, but a refusal says the option's range (a bounded one) as what is accepted, not a bare example.
double parse_real_option(std::string_view field, std::string_view text, const OptionRange& range);
// The comma-separated items of a list option's text ("K0,K2,K3"); OptionError naming `field` for an empty item
// ("K0,,K2", "K0,": a typing error, not a shorter list).
std::vector<std::string> split_option_list(std::string_view field, std::string_view text);
// The index of `text` among `names`; OptionError listing the names otherwise.
std::size_t parse_choice_option(std::string_view field, std::string_view text,
                                std::span<const std::string_view> names);

// Throws OptionError(field, value_text, ...) unless range accepts value (a non-finite value never is).
void check_option_value(std::string_view field, double value, const std::string& value_text,
                        const OptionRange& range);

// The text of an option's number: an integer in full (not through a double), a double as option_number_text.
template <class Number>
std::string option_value_text(Number value) {
  if constexpr (std::is_integral_v<Number>)
    return std::to_string(value);
  else
    return option_number_text(double(value));
}

// --- implementation of the template ---

template <class Options>
void check_options(const Options& options, OptionTable<Options> table) {
  for (const OptionSpec<Options>& row : table) {
    std::visit(
        [&](auto member) {
          if constexpr (std::is_same_v<decltype(member), OptionEnum<Options>>) {
            return;  // set only by name (parse_choice_option)
          } else {
            check_member(member.of(options), row);
          }
        },
        row.member);
  }
}

template <class Options>
std::vector<std::string> option_arguments(const Options& options, OptionTable<Options> table,
                                          const Options& defaults) {
  std::vector<std::string> arguments;
  const auto joined = [](const auto& list) {
    std::string text;
    for (const auto& item : list) {
      if (!text.empty()) text += ',';
      if constexpr (std::is_arithmetic_v<std::remove_cvref_t<decltype(item)>>)
        text += option_value_text(item);
      else
        text += item;
    }
    return text;
  };
  for (const OptionSpec<Options>& row : table) {
    const std::string flag = option_flag(row.field);
    std::visit(
        [&](auto member) {
          if constexpr (std::is_same_v<decltype(member), OptionEnum<Options>>) {
            const auto index = member.get(options);
            if (index && index != member.get(defaults))
              arguments.insert(arguments.end(), {flag, std::string(member.names[*index])});
          } else {
            using Field = typename decltype(member)::type;
            const Field& value = member.of(options);
            if (value == member.of(defaults)) return;
            if constexpr (std::is_same_v<Field, bool>) {
              if (value) arguments.push_back(flag);  // a switch is off by default
            } else if constexpr (std::is_same_v<Field, std::string>) {
              arguments.insert(arguments.end(), {flag, value});
            } else if constexpr (std::is_same_v<Field, std::vector<std::string>>) {
              for (const std::string& item : value) arguments.insert(arguments.end(), {flag, item});
            } else if constexpr (std::is_same_v<Field, std::vector<double>>) {
              arguments.insert(arguments.end(), {flag, joined(value)});
            } else if constexpr (std::is_arithmetic_v<Field>) {
              arguments.insert(arguments.end(), {flag, option_value_text(value)});
            } else if constexpr (std::is_same_v<Field, std::optional<std::vector<std::string>>>) {
              if (value) arguments.insert(arguments.end(), {flag, joined(*value)});
            } else {  // an optional number
              if (value) arguments.insert(arguments.end(), {flag, option_value_text(*value)});
            }
          }
        },
        row.member);
  }
  return arguments;
}

template <class Field, class Options>
void check_member(const Field& value, const OptionSpec<Options>& row) {
  if constexpr (std::is_same_v<Field, bool> || std::is_same_v<Field, std::string>) {
    // no range
  } else if constexpr (std::is_same_v<Field, std::vector<std::string>>) {
    if (row.required && value.empty())
      throw OptionError(std::string(row.field), "",
                        "none given; accepted: at least one " + std::string(row.value_name));
  } else if constexpr (std::is_same_v<Field, std::optional<std::vector<std::string>>>) {
    if (row.required && value && value->empty())  // unset: the verb's own default (a file's terms)
      throw OptionError(std::string(row.field), "",
                        "none given; accepted: at least one " + std::string(row.value_name));
  } else if constexpr (std::is_same_v<Field, std::vector<double>>) {
    for (double x : value) check_option_value(row.field, x, option_value_text(x), row.range);
  } else if constexpr (std::is_arithmetic_v<Field>) {
    // A 64-bit integer beyond 2^53 is compared as its nearest double: the ranges' ends are exact.
    check_option_value(row.field, double(value), option_value_text(value), row.range);
  } else {  // std::optional of a number
    if (value) check_option_value(row.field, double(*value), option_value_text(*value), row.range);
  }
}

}  // namespace ccal

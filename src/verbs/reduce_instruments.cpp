#include "reduce_instruments.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "ccal/core/errors.hpp"
#include "ccal/intake/measured_inputs.hpp"

namespace ccal::verbs {

namespace {

// The options of one instrument: the logs read through its column of the layout's [instruments].
ReduceOptions instrument_options(const Config& instrument, const ReduceOptions& o) {
  const auto& columns = o.layout.instruments;
  const auto found = std::find_if(columns.begin(), columns.end(),
                                  [&](const LogLayout::InstrumentColumn& c) { return c.id == instrument.instrument_id; });
  const std::string where = o.logs.empty() || o.logs.front().manifest.empty() ? std::string("the log layout")
                                                                               : o.logs.front().manifest;
  if (found == columns.end())
    throw InputError(fmt::format(
        "{}: [instruments]: no output column for instrument '{}' of {}; accepted: {} = {{ pulses = \"…\" }} or "
        "{} = {{ output = \"…\" }}, the column of its output in every log",
        where, instrument.instrument_id, instrument.source, instrument.instrument_id, instrument.instrument_id));
  ReduceOptions one = o;
  one.layout.instruments.clear();
  // Its column is the log's pulses or output column; the other name is "", which no column has (a header's
  // names are never empty), so that another instrument's column is never taken for it.
  LogColumns& c = one.layout.columns;
  (found->pulses ? c.pulses : c.output) = found->column;
  (found->pulses ? c.output : c.pulses).clear();
  return one;
}

// The warnings of a test's reductions: one that every instrument gives alike is of the logs they share (a run's
// gap, its control), said once; the others are each instrument's, named by it.
std::vector<std::string> test_warnings(std::vector<ReduceResult>& each) {
  const auto everyones = [&](const std::string& w) {
    return std::ranges::all_of(
        each, [&](const ReduceResult& one) { return std::ranges::find(one.warnings, w) != one.warnings.end(); });
  };
  std::vector<std::string> out;
  for (const std::string& w : each.front().warnings)
    if (everyones(w)) out.push_back(w);
  for (const ReduceResult& one : each)
    for (const std::string& w : one.warnings)
      if (!everyones(w)) out.push_back(fmt::format("instrument {}: {}", one.config.instrument_id, w));
  for (ReduceResult& one : each)
    for (std::string& w : one.warnings) w = fmt::format("instrument {}: {}", one.config.instrument_id, w);
  return out;
}

// The ids of the instruments of a test, the chosen one's and the others'.
std::vector<std::string> test_ids(const Config& cfg) {
  std::vector<std::string> ids;
  for (const Config& one : cfg.instruments) ids.push_back(one.instrument_id);
  for (const Config::OtherInstrument& other : cfg.other_instruments) ids.push_back(other.id);
  return ids;
}

}  // namespace

void check_single_instrument_output(const Config& cfg, std::string_view field) {
  if (cfg.instruments.size() <= 1) return;
  throw OptionError(std::string(field), "",
                    fmt::format("{} holds {} instruments, each with a table of its own; accepted: {} json, which "
                                "holds every instrument's observations and statement, or {} ID for one of them",
                                cfg.source, cfg.instruments.size(), OptionError::name("format"),
                                OptionError::name("instrument")));
}

ReduceResult reduce_instruments(const Config& cfg, const ReduceOptions& o) {
  for (const auto& column : o.layout.instruments)
    if (std::none_of(cfg.instruments.begin(), cfg.instruments.end(),
                     [&](const Config& c) { return c.instrument_id == column.id; }) &&
        std::ranges::find(cfg.other_instruments, column.id, &Config::OtherInstrument::id) == cfg.other_instruments.end())
      throw InputError(fmt::format("{}:{}: [instruments]: '{}' is no instrument of {}; accepted: the ids of its "
                                   "[[instruments]] ({})",
                                   o.logs.empty() ? std::string("the log layout") : o.logs.front().manifest,
                                   column.line, column.id, cfg.source, fmt::join(test_ids(cfg), ", ")));
  if (cfg.instruments.size() == 1) {
    // One instrument (one [[instruments]] entry, or one chosen from a test of several): reduced as a configuration
    // of one, through its column of the layout's [instruments] when the layout maps them.
    Config alone = cfg.instruments.front();
    alone.instruments.clear();
    return reduce(alone, o.layout.instruments.empty() ? o : instrument_options(alone, o));
  }
  std::vector<ReduceResult> each;
  std::vector<Config> charged;  // each instrument's configuration with the inputs its logs measured
  for (const Config& instrument : cfg.instruments) {
    each.push_back(reduce(instrument, instrument_options(instrument, o)));
    charged.push_back(with_measured_inputs(instrument, measured_inputs(instrument, each.back().logs)));
  }
  ReduceResult r = each.front();
  r.warnings = test_warnings(each);
  if (o.statement) {
    const StatementOptions& so = o.statement_options;
    r.covariance = instrument_covariance(
        charged, r.mode, std::uint64_t(std::max<std::int64_t>(so.trials(), 0)), so.seed.value_or(kDefaultSeed),
        so.threads.value_or(0));
  }
  r.config = cfg;
  r.instruments = std::move(each);
  return r;
}

}  // namespace ccal::verbs

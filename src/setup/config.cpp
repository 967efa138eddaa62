#include "ccal/setup/config.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"

namespace ccal {

void require_one_instrument(const Config& config, std::string_view verb) {
  if (config.instruments.size() <= 1) return;  // one [instrument], or one [[instruments]] entry
  std::vector<std::string> ids;
  for (const Config& one : config.instruments) ids.push_back(one.instrument_id);
  throw OptionError("instrument", "",
                    fmt::format("missing: {} holds a test of {} instruments ({}), and {} answers for one at a time; "
                                "accepted: one of {}",
                                config.source, config.instruments.size(), fmt::join(ids, ", "), verb,
                                fmt::join(ids, ", ")));
}

Config select_instrument(const Config& config, std::string_view id) {
  if (id.empty()) return config;
  if (config.instruments.empty())
    throw OptionError("instrument", std::string(id),
                      fmt::format("names an instrument, but {} has one [instrument] and no ids; accepted: no "
                                  "instrument option, or a configuration of [[instruments]]",
                                  config.source));
  std::vector<std::string> ids;
  for (const Config& one : config.instruments) ids.push_back(one.instrument_id);
  const auto chosen = std::find(ids.begin(), ids.end(), id);
  if (chosen == ids.end())
    throw OptionError("instrument", std::string(id),
                      fmt::format("is no instrument of {}; accepted: {}", config.source, fmt::join(ids, ", ")));
  Config one = config.instruments[std::size_t(chosen - ids.begin())];
  one.instruments = {one};
  for (const Config& other : config.instruments)
    if (other.instrument_id != id) one.other_instruments.push_back({other.instrument_id, other.numbers_sha256});
  return one;
}

void clear_fingerprints(Config& config) {
  config.text_sha256.clear();
  config.numbers_sha256.clear();
  config.setup_sha256.clear();
}

std::size_t select_run(const TestPlan& plan, std::string_view name_or_index, std::string_view option_name) {
  for (std::size_t k = 0; k < plan.runs.size(); ++k)
    if (plan.runs[k].name == name_or_index) return k;
  std::size_t index = 0;
  const auto [end, ec] =
      std::from_chars(name_or_index.data(), name_or_index.data() + name_or_index.size(), index);
  if (ec == std::errc{} && end == name_or_index.data() + name_or_index.size() && index >= 1 &&
      index <= plan.runs.size())
    return index - 1;
  std::string names;
  for (const Run& r : plan.runs) {  // appended piecewise: GCC 12 misreads "…" + string here (-Wrestrict)
    if (!names.empty()) names += ", ";
    names += r.name;
  }
  throw OptionError(std::string(option_name), fmt::format("'{}'", name_or_index),
                    fmt::format("is no run; accepted: a run name ({}) or an index 1..{}", names, plan.runs.size()));
}

Experiment Config::experiment() const {
  Experiment ex;
  ex.geometry = centrifuge.geometry;
  ex.layout = centrifuge.layout;
  ex.site = site;
  ex.plan = plan;
  ex.instrument = instrument;
  ex.rate_noise = centrifuge.rate_noise;
  ex.chain = chain;
  return ex;
}

}  // namespace ccal

#include "ccal/io/truth_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "ccal/core/sha256.hpp"
#include "config_reader.hpp"

namespace ccal {

using namespace config_reading;

SimulationTruth parse_truth(std::string_view text, std::string_view source_name, const Config& config) {
  const Reader r{std::string(source_name)};
  const toml::table root =
      parse_toml(r, text, source_name, "a truth file in TOML: [errors] with the values the simulated machine has");
  // A truth file holds the machine's errors only: the rest of a configuration is the lab's, not the truth's.
  for (const auto& [key, node] : root)
    if (key.str() != "errors" && std::find(kRootKeys.begin(), kRootKeys.end(), key.str()) != kRootKeys.end())
      r.fail(where(key.source()), key.str(),
             "a configuration's table, not a truth's; accepted: [errors] only, the values the simulated machine "
             "has (the rest of the set-up is the configuration's)");
  r.check_keys(root, "", Keys{"errors"});
  // An empty file (/dev/null, one truncated to nothing) would simulate a machine without errors unasked.
  if (!root.contains("errors"))
    throw InputError(fmt::format("{}:1: a truth file without an [errors] table (it is empty); accepted: [errors] "
                                 "with the values the simulated machine has (an empty [errors] table for a machine "
                                 "without errors)",
                                 source_name));
  CentrifugeModel machine = config.centrifuge;
  machine.errors.setZero();
  std::vector<std::pair<int, double>> chain_errors;
  read_errors(r, root, config, machine, &chain_errors);
  return {std::string(source_name), sha256_hex(text), machine.errors, std::move(chain_errors)};
}

SimulationTruth load_truth(const std::filesystem::path& path, const Config& config) {
  return parse_truth(read_file_text(path), path.string(), config);
}

}  // namespace ccal

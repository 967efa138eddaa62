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
  toml::table root;
#if TOML_EXCEPTIONS
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    r.fail(where(e.source()), "", fmt::format("TOML syntax error: {}", e.description()));
  }
#else
  auto result = toml::parse(text, source_name);
  if (!result)
    r.fail(where(result.error().source()), "",
           fmt::format("TOML syntax error: {}", result.error().description()));
  root = std::move(result).table();
#endif
  // A truth file holds the machine's errors only: the rest of a configuration is the lab's, not the truth's.
  for (const auto& [key, node] : root)
    if (key.str() != "errors" && std::find(kRootKeys.begin(), kRootKeys.end(), key.str()) != kRootKeys.end())
      r.fail(where(key.source()), key.str(),
             "a configuration's table, not a truth's; accepted: [errors] only, the values the simulated machine "
             "has (the rest of the set-up is the configuration's)");
  r.check_keys(root, "", Keys{"errors"});
  CentrifugeModel machine = config.centrifuge;
  machine.errors.setZero();
  read_errors(r, root, machine);
  return {std::string(source_name), sha256_hex(text), machine.errors};
}

SimulationTruth load_truth(const std::filesystem::path& path, const Config& config) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec))
    throw FileNotFound<ConfigError>(name, 0, 0, "", "cannot read the file; check the path and permissions");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw FileNotFound<ConfigError>(name, 0, 0, "", "cannot read the file; check the path and permissions");
  return parse_truth(text.str(), name, config);
}

}  // namespace ccal

#pragma once
// The configuration file (TOML) → Config (setup/config.hpp); docs/config.md has the full schema.
//
// Every physical value in a configuration file is a string with a unit ("2.5 m", "2 arcsec", "30 g",
// "0.003 deg/s/g^3"); it is converted to SI on reading, with its dimension checked, so that nothing inside
// ccal ever sees an engineering unit. Anything ccal cannot accept stops the load with a ConfigError whose
// message is one line:
//     <file>:<line>:<col>: <key path>: <what is wrong>; <what is accepted>
// e.g.  examples/x.toml:12:1: centrifuge.radious: unknown key; did you mean 'radius'?
//
// Usage:
//     const ccal::Config cfg = ccal::load_config("examples/wang_ren_2014.toml");
//     for (const ccal::Run& run : cfg.plan.runs) { ... ccal::initial_phase(run, cfg.centrifuge.geometry,
//                                                  cfg.site) ... }

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/setup/config.hpp"

namespace ccal {

// A configuration that cannot be accepted. what() is the one-line message above; the parts are kept for
// programs that want them. line and column are 1-based, 0 when the problem has no place in the file (e.g.
// a file that cannot be read).
class ConfigError : public LocatedInputError {
 public:
  ConfigError(std::string source, int line, int column, std::string key, std::string problem);

  const std::string& key() const noexcept { return item(); }
};

// Reads and checks a configuration file. Throws ConfigError (also when the file cannot be read).
Config load_config(const std::filesystem::path& path);

// Parses configuration text; source_name stands for the file name in messages and Config::source.
Config parse_config(std::string_view text, std::string_view source_name);

// The paper's set-up (examples/wang_ren_2014.toml), embedded in the library at build time.
std::string_view bundled_example_text() noexcept;
Config bundled_example();
inline constexpr std::string_view kBundledExampleName = "bundled:wang_ren_2014.toml";

// Edit distance (insertions, deletions, substitutions) between two strings, used to suggest keys.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The did-you-mean of a mistyped name (a command, an option): the name at the least edit distance d from
// `typed` (the first of those tied) if 3·d <= its length, i.e. at most a third of it is wrong; else the only
// name that starts with `typed` (an abbreviation); else nullopt.
std::optional<std::string> nearest_name(std::string_view typed, std::span<const std::string> names);

}  // namespace ccal

#pragma once
// A simulation's truth (docs/config.md, "The simulation's truth"): what the simulated centrifuge really has,
// apart from what the laboratory knows. The configuration's `[errors]` are the errors the lab has measured
// (compensated in the model, or corrected in the statement); the truth file's `[errors]` are the values the
// simulated machine has, which no lab knows. Only `ccal simulate --truth FILE` (and Python's simulate(…,
// truth=…)) reads it: `reduce`, `identify` and `report` never do, so nothing the lab did not state is corrected.
//
//     # lab_truth.toml
//     [errors]
//     dthz5 = "1.5 arcsec"      # the same ids and units as a configuration's [errors]
//
// Without a truth file a simulation's machine has the configuration's [errors]: the lab's measurements are
// then taken as exact.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

#include "ccal/io/config_file.hpp"

namespace ccal {

struct SimulationTruth {
  std::string source;       // the file's name, as in messages
  std::string text_sha256;  // of the file's text
  Eigen::VectorXd errors;   // per parameter of the configuration's layout (SI); every one not listed is 0
  // The measuring chain's errors (truth minus the lab's value: g, time_base, output_gain, a fixed term, an
  // encoder's, a declared input's), by parameter code (setup/measuring_chain.hpp), SI.
  std::vector<std::pair<int, double>> chain_errors;
};

// Reads a truth file against the configuration whose layout (harmonic order) names its parameters. Throws
// ConfigError, located as a configuration's are, for a file that cannot be read, a TOML error, a key other than
// [errors], or an [errors] entry a configuration's [errors] would refuse.
SimulationTruth load_truth(const std::filesystem::path& path, const Config& config);
SimulationTruth parse_truth(std::string_view text, std::string_view source_name, const Config& config);

}  // namespace ccal

// Loads the bundled example through the installed library and prints the nominal main-axis rate of its 20 g
// run.
#include <cstdio>

#include "ccal/io/config_file.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/version.hpp"

#ifdef CCAL_SOURCE_DIR
#error "the installed ccal::ccal passes a path of the machine that built it (CCAL_SOURCE_DIR)"
#endif

int main() {
  const ccal::Config config = ccal::bundled_example();
  const ccal::Run& run = config.plan.runs.at(ccal::select_run(config.plan, "20g", "run"));
  std::printf("%s\nrate %.9f rad/s\n", ccal::version_line().c_str(),
              ccal::nominal_rate(run, config.centrifuge.geometry, config.site));
}

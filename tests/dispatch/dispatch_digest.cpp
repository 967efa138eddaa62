// The bits of the library's cloned loops (core/cloned_loops.hpp) as one SHA-256, and the clone this processor
// runs: tests/dispatch/check_dispatch_targets.py runs it natively and on emulated processors that lack AVX-512
// or AVX2, and requires one digest of all. Its work: Φ⁻¹ of the Monte Carlo's draws over the grid and its tails
// (draw_quantiles.cpp), and the Monte Carlo of the bundled example, its sources independent and then all
// correlated through the Gaussian copula (the drives' rate-noise derivatives, the run means' node loops, the
// tracked sines and cosines), every trial's outputs and the statistics; and the
// statement's Monte Carlo check of the lab example (its multivariate t). Usage: dispatch_digest [trials].
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "../../src/uncertainty/draw_quantiles.hpp"
#include "ccal/core/sha256.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"

namespace {

// The clone GCC's resolver picks for target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default").
const char* dispatch_target() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return "x86-64-v4";
  if (__builtin_cpu_supports("x86-64-v3")) return "x86-64-v3";
#endif
  return "default";
}

void add(ccal::Sha256& hash, const double* v, std::size_t n) {
  hash.update(std::string_view(reinterpret_cast<const char*>(v), n * sizeof(double)));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace ccal;
  const std::uint64_t trials = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 2000;
  Sha256 hash;
  {  // Φ⁻¹ on the grid u = (k + ½)·2⁻⁵²: its first points, log-uniform tails and the middle
    std::vector<double> u;
    for (int k = 0; k < 20000; ++k) u.push_back((double(k) + 0.5) * 0x1p-52);
    for (int k = 0; k < 20000; ++k) u.push_back((std::floor(std::exp2(52.0 * k / 20000)) + 0.5) * 0x1p-52);
    for (int k = 0; k < 20000; ++k) u.push_back((std::floor(0x1p52 * (k + 0.5) / 20000) + 0.5) * 0x1p-52);
    std::vector<double> x(u.size());
    draws::normal_quantiles(u.data(), x.data(), u.size());
    add(hash, x.data(), x.size());
  }
  Config cfg = bundled_example();
  for (int correlated = 0; correlated < 2; ++correlated) {  // the bundled example's Monte Carlo
    if (correlated)  // r = 0.3 between every pair of tolerances: every source through the Gaussian copula
      for (std::size_t a = 0; a < cfg.tolerances.size(); ++a)
        for (std::size_t b = a + 1; b < cfg.tolerances.size(); ++b)
          cfg.correlations.push_back({cfg.tolerances[a].id, cfg.tolerances[b].id, 0.3});
    const CalibrationModel model = calibration_model(cfg);
    PropagationOptions o;
    o.trials = trials;
    o.threads = 1;
    o.keep_samples = true;
    const MonteCarloDetail r = run_monte_carlo(monte_carlo_sources(cfg), cfg.correlations, model.n_outputs(),
                                               model.output_names(), calibration_trial(model), o);
    add(hash, r.samples.data(), std::size_t(r.samples.size()));
    for (const OutputSummary& s : r.outputs) {
      const double v[] = {s.mean, s.std_dev, s.low_symmetric, s.high_symmetric};
      add(hash, v, 4);
    }
  }
  {  // the statement's check on the lab example
    const Config lab = load_config(CCAL_SOURCE_DIR "/examples/lab.toml");
    const verbs::Identification id = verbs::simulate(lab).identification;
    verbs::StatementOptions o;
    o.threads = 1;
    o.statement_trials = std::int64_t(trials);
    const verbs::CalibrationStatement s = verbs::calibration_statement(lab, id, o, "statement");
    for (const CoefficientStatement& c : s.coefficients) {
      if (!c.monte_carlo) continue;
      const OutputSummary& mc = *c.monte_carlo;
      const double v[] = {mc.mean, mc.std_dev, mc.low_symmetric, mc.high_symmetric, double(c.monte_carlo_trials)};
      add(hash, v, 5);
    }
  }
  std::printf("%s %s\n", dispatch_target(), hash.hex().c_str());
  return 0;
}

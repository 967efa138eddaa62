#include "ccal/uncertainty/chain_inputs.hpp"

#include <algorithm>
#include <cmath>

#include "ccal/setup/input_description.hpp"
#include "ccal/uncertainty/budget.hpp"

namespace ccal {

namespace {

// The model's regressor column of a term (free or fixed), or nothing when the spec has no such column.
const double* regressor_column(const Observations<double>& obs, const std::string& term, Eigen::Index& col) {
  const auto it = std::find(obs.columns.begin(), obs.columns.end(), term);
  if (it == obs.columns.end()) return nullptr;
  col = Eigen::Index(it - obs.columns.begin());
  return obs.regressors.col(col).data();
}

// The fourth-order central difference of f at 0 with step h: f′(0) + O(h⁴ f⁽⁵⁾).
template <class F>
Eigen::VectorXd central_difference(F f, double h) {
  return (8.0 * (f(h) - f(-h)) - (f(2 * h) - f(-2 * h))) / (12.0 * h);
}

// ∂ȳ/∂g by a central difference of the exact chain, h = 1e-3 g: the run means are smooth in g (a polynomial in
// 1/g for a polynomial instrument), so the truncation, O(h⁴), stays near 1e-12 of the column and the round-off
// near 1e-13 (tests/uncertainty/chain_inputs_test.cpp checks it against minus the radius's column, exact by AD).
Eigen::VectorXd gravity_column(const Experiment& ex, const IdentificationSpec& spec, const Eigen::VectorXd& at,
                               const Eigen::VectorXd& known, ModelMode mode, const ReductionOptions& reduction) {
  return central_difference(
      [&](double dg) {
        return Eigen::VectorXd(
            observe<double>(with_gravity_error(ex, dg), ex, at, known, spec, mode, reduction).output);
      },
      1e-3 * ex.site.g);
}

// The runs a clock fast by τ makes the model see: each lasts T (1 + τ) on that clock, from the same angles, and
// a drive whose rate the encoder measured turns at its rate / (1 + τ) (its error too), so that it sweeps the
// same angles as the machine did.
Experiment clock_model(const Experiment& ex, const Eigen::VectorXd& known, double tau, Eigen::VectorXd& errors) {
  Experiment out = ex;
  errors = known;
  for (Run& run : out.plan.runs) {
    run.initial_phase = initial_phase(run, ex.geometry, ex.site);
    run.terminal_phase.reset();
    run.duration *= 1 + tau;
    if (ex.chain.main_rate_measured) run.g_level /= (1 + tau) * (1 + tau);
  }
  if (ex.chain.main_rate_measured) errors[ex.layout.static_index(ch::domega)] /= 1 + tau;
  if (ex.chain.platform_rate_measured) errors[ex.layout.static_index(ch::dOmega)] /= 1 + tau;
  return out;
}

// ∂ȳ/∂τ: the model's prediction moves with the runs it sees (clock_model), which the truth's column is minus
// of, and a counted output is read / (1 + τ). A central difference with h = 1e-4 (the run means are smooth in
// the duration and the rate; truncation O(h⁴)).
Eigen::VectorXd time_base_column(const Experiment& ex, const IdentificationSpec& spec, const Eigen::VectorXd& known, ModelMode mode, const ReductionOptions& reduction,
                                 const Eigen::VectorXd& output) {
  Eigen::VectorXd column = -central_difference(
      [&](double tau) {
        Eigen::VectorXd errors;
        const Experiment model = clock_model(ex, known, tau, errors);
        return Eigen::VectorXd(observe<double>(model, model, errors, errors, spec, mode, reduction).output);
      },
      1e-4);
  if (output_read_against_clock(ex.instrument)) column -= output;
  return column;
}

// The ripple harmonics of the layout that the encoder inputs among `parameters` act through (each once, in
// the order first met; none beyond the layout's harmonic order).
std::vector<int> encoder_layout_columns(const std::vector<int>& parameters, const ErrorLayout& layout) {
  std::vector<int> through;
  for (int p : parameters) {
    const ChainInput in = chain_input(p);
    if (in.kind != ChainKind::encoder) continue;
    const EncoderTerm t = encoder_term(in.index);
    const int channel = t.drive == 1 ? ch::ripple1 : ch::ripple3;
    if (t.harmonic > layout.harmonic_order()) continue;
    const int column = layout.harmonic_index(channel, t.harmonic, !t.is_sine);
    if (std::find(through.begin(), through.end(), column) == through.end()) through.push_back(column);
  }
  return through;
}

}  // namespace

bool output_read_against_clock(const InstrumentModel& instrument) { return instrument.quantum > 0; }

Experiment with_gravity_error(const Experiment& ex, double dg) {
  Experiment out = ex;
  const double scale = ex.site.g / (ex.site.g + dg);
  out.site.g = ex.site.g + dg;
  // The g-levels are in the local g unless the coefficients are per standard gravity, which g does not move.
  if (!(ex.site.unit_g > 0))
    for (Run& run : out.plan.runs) run.g_level *= scale;
  return out;
}

Experiment with_chain_errors(const Experiment& ex, const std::vector<std::pair<int, double>>& errors) {
  Experiment out = ex;
  auto move_term = [&](const std::string& term, double by) {
    const auto& ids = out.instrument.term_ids;
    const auto it = std::find(ids.begin(), ids.end(), term);
    if (it != ids.end()) out.instrument.coefficients[Eigen::Index(it - ids.begin())] += by;
  };
  double dg = 0;
  for (const auto& [code, value] : errors) {
    const ChainInput in = chain_input(code);
    if (in.kind == ChainKind::gravity) dg += value;
    if (in.kind == ChainKind::time_base)
      for (Run& run : out.plan.runs) {
        run.initial_phase = initial_phase(run, ex.geometry, ex.site);
        run.terminal_phase.reset();
        run.duration /= 1 + value;
      }
    if (in.kind == ChainKind::fixed_term) move_term(all_term_ids().at(std::size_t(in.index)), value);
    if (in.kind == ChainKind::declared)
      for (const auto& [term, s] : ex.chain.declared.at(std::size_t(in.index)).sensitivity) move_term(term, s * value);
  }
  return dg != 0 ? with_gravity_error(out, dg) : out;
}

void read_through_chain(Eigen::VectorXd& means, const InstrumentModel& instrument,
                        const std::vector<std::pair<int, double>>& errors) {
  for (const auto& [code, value] : errors) {
    const ChainKind kind = chain_input(code).kind;
    if (kind == ChainKind::output_gain) means *= 1 + value;
  }
  for (const auto& [code, value] : errors)
    if (chain_input(code).kind == ChainKind::output_offset) means.array() += value;
  if (output_read_against_clock(instrument))
    for (const auto& [code, value] : errors)
      if (chain_input(code).kind == ChainKind::time_base) means /= 1 + value;
}

Eigen::MatrixXd chain_output_columns(const Experiment& ex, const IdentificationSpec& spec,
                                     const std::vector<int>& parameters, const Eigen::VectorXd& at,
                                     ModelMode mode, const ReductionOptions& reduction) {
  const auto runs = Eigen::Index(ex.plan.runs.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(runs, Eigen::Index(parameters.size()));
  if (parameters.empty()) return out;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());
  const Observations<double> obs = observe<double>(ex, at, known, spec, mode, reduction);
  const ErrorLayout& layout = ex.layout;
  // The layout columns the encoders' errors go through, in one AD pass.
  const std::vector<int> through = encoder_layout_columns(parameters, layout);
  const Eigen::MatrixXd J =
      through.empty() ? Eigen::MatrixXd()
                      : output_jacobian(ex, spec, through, at, mode, reduction, DerivativeMethod::automatic, false)
                            .total;
  for (std::size_t c = 0; c < parameters.size(); ++c) {
    auto column = out.col(Eigen::Index(c));
    const ChainInput in = chain_input(parameters[c]);
    switch (in.kind) {
      case ChainKind::output_gain:
        column = obs.output;
        break;
      case ChainKind::output_offset:
        column.setOnes();
        break;
      case ChainKind::time_base:
        column = time_base_column(ex, spec, known, mode, reduction, obs.output);
        break;
      case ChainKind::fixed_term: {
        Eigen::Index col = 0;
        if (regressor_column(obs, all_term_ids().at(std::size_t(in.index)), col)) column = obs.regressors.col(col);
        break;
      }
      case ChainKind::gravity:
        column = gravity_column(ex, spec, at, known, mode, reduction);
        break;
      case ChainKind::encoder: {
        const EncoderTerm t = encoder_term(in.index);
        const bool measured = t.drive == 1 ? ex.chain.main_ripple_measured : ex.chain.platform_ripple_measured;
        if (!measured || t.harmonic > layout.harmonic_order()) break;
        const int channel = t.drive == 1 ? ch::ripple1 : ch::ripple3;
        const int p = layout.harmonic_index(channel, t.harmonic, !t.is_sine);
        const auto d = Eigen::Index(std::find(through.begin(), through.end(), p) - through.begin());
        // c cos kq + s sin kq is read as the ripple (k s, −k c); the truth's ripple is the model's less it.
        column = (t.is_sine ? -double(t.harmonic) : double(t.harmonic)) * J.col(d);
        break;
      }
      case ChainKind::declared:
        for (const auto& [term, s] : ex.chain.declared.at(std::size_t(in.index)).sensitivity) {
          Eigen::Index col = 0;
          if (regressor_column(obs, term, col)) column += s * obs.regressors.col(col);
        }
        break;
    }
  }
  return out;
}

}  // namespace ccal

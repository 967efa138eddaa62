#pragma once
// Accelerometer models (docs/model.md §7): the paper's PIGA, Eq.(2),
//     α = K0 + K1 a_i + K2 a_i² + K3 a_i³ + s_ω ω_IA  (+ −ΔΩ in paper mode)
// and an IEEE-style term list (IEEE Std 836/1293 pendulous form extended to the PIGA):
//     E = Σ K_n a_iⁿ + K_oq |a_i| a_i + K_p a_p + K_o a_o + K_ip a_i a_p + K_io a_i a_o + K_pp a_p²
//         + K_oo a_o² + K_po a_p a_o + K_w ω_IA
// Inputs a_i, a_p, a_o are specific force along IA, PA, OA in g; ω_IA in rad/s. Coefficients are stored in SI
// output units per gⁿ (rad/s/gⁿ for a PIGA whose output is a rate, g/gⁿ for an accelerometer read in g).
// Term ids are stable: "K0".."K10", "K_oq", "K_p", "K_o", "K_ip", "K_io", "K_pp", "K_oo", "K_po", "K_w".

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/frames.hpp"

namespace ccal {

enum class TermKind { power, abs_square, p, o, ip, io, pp, oo, po, rate };

struct TermSpec {
  TermKind kind = TermKind::power;
  int power = 0;  // for TermKind::power: the exponent n of a_iⁿ
};

// Parses a term id; nullopt if it is not one (see the list above).
// The unit of a term's coefficient for an instrument read in `output_unit`: the output unit per gⁿ for a
// term of order n in the specific force (e.g. "deg/s/g^3" for K3 of a PIGA read in deg/s), per (rad/s) for
// K_w; "" when the output unit is not known. g: the symbol of the g the coefficients are per, "g" for the local
// g, "gn" for standard gravity (InstrumentModel::g_symbol).
std::string coefficient_unit(std::string_view output_unit, const TermSpec& term, std::string_view g = "g");
// The same for a term id, which must be valid.
std::string coefficient_unit(std::string_view output_unit, std::string_view term_id, std::string_view g = "g");

std::optional<TermSpec> parse_term(std::string_view id);
std::string term_id(const TermSpec& term);
// Every term id in canonical order: K0 … K10, then K_oq, K_p, K_o, K_ip, K_io, K_pp, K_oo, K_po, K_w.
std::vector<std::string> all_term_ids();
// Position of a term in that order.
int term_rank(const TermSpec& term);
// The highest power of the input the term list allows (K0..K10).
inline constexpr int kMaxPower = 10;

// Value of a term's regressor at specific force a = (a_i, a_p, a_o) [g] and IA rate w_ia [rad/s].
template <class S>
S term_regressor(const TermSpec& t, const Vec3<S>& a, const S& w_ia) {
  using std::abs;
  switch (t.kind) {
    case TermKind::power: {
      S r{1};
      for (int k = 0; k < t.power; ++k) r *= a[0];
      return r;
    }
    case TermKind::abs_square:
      return abs(a[0]) * a[0];
    case TermKind::p:
      return a[1];
    case TermKind::o:
      return a[2];
    case TermKind::ip:
      return a[0] * a[1];
    case TermKind::io:
      return a[0] * a[2];
    case TermKind::pp:
      return a[1] * a[1];
    case TermKind::oo:
      return a[2] * a[2];
    case TermKind::po:
      return a[1] * a[2];
    case TermKind::rate:
      return w_ia;
  }
  return S{0};
}

struct InstrumentModel {
  std::string name = "PIGA";
  // Output unit as the user writes it ("deg/s", "g", "pulse/s"); values inside are SI (rad/s, g, 1/s).
  std::string output_unit = "deg/s";
  std::vector<std::string> term_ids;  // e.g. {"K0", "K1", "K2", "K3"}
  Eigen::VectorXd coefficients;       // SI, one per term
  // s_ω: gain of the inertial rate about the IA in the output (output SI per rad/s). +1 for a PIGA read as an
  // outer-gimbal rate (the paper's sign, model.md A5); 0 for an accelerometer that does not sense rate.
  double rate_gain = 1.0;
  // Output noise for simulation: white-noise density [output SI/√Hz] and quantisation step of the integrated
  // output [output SI·s] (e.g. a PIGA pulse weight); both 0 = noise-free.
  double noise_density = 0.0;
  double quantum = 0.0;
  // A current output read as the voltage across this resistor [ohm] (a DVM on a sampling resistor): the logs'
  // output column is then in volts, I = V/R; 0: the logs hold the output itself.
  double sampling_resistor = 0.0;
  // The g its coefficients are per, as a unit symbol: "g" the site's local g, "gn" standard gravity
  // ([site] g_unit; Site::unit_g).
  std::string g_symbol = "g";

  std::vector<TermSpec> terms() const;
  std::optional<double> coefficient(std::string_view id) const;
};

// Output of the instrument at one instant [output SI].
template <class S>
S instrument_output(const InstrumentModel& model, const std::vector<TermSpec>& terms, const Vec3<S>& a,
                    const S& w_ia) {
  S out = S(model.rate_gain) * w_ia;
  for (std::size_t k = 0; k < terms.size(); ++k)
    out += S(model.coefficients[Eigen::Index(k)]) * term_regressor(terms[k], a, w_ia);
  return out;
}

// The paper's PIGA (model.md §7.1): K0 = 0.061973 °/s, K1 = 505.2097 °/s/g, K2 = 0.02 °/s/g², K3 = 0.003
// °/s/g³, s_ω = +1.
InstrumentModel paper_piga();

}  // namespace ccal

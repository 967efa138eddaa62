#pragma once
// The inputs of the measuring chain (docs/model.md §10.7): what a calibration depends on besides the
// centrifuge's errors. Each is a source of the budget like a centrifuge error ([tolerances] id, distribution,
// group, correlations, cost) and an error of a simulated machine (truth minus the lab's value):
//   g               local gravity of [site], m/s²: the unit of the g-levels and of the coefficients
//   time_base       relative frequency error of the clock that timestamps the logs (rates read against it)
//   output_gain     relative error of the output's reading (a DVM's gain, a sampling resistor, a gate)
//   output_offset   offset of the output's reading, in the output's unit
//   K<n>, K_w, …    a fixed term's value (from another calibration), in its unit
//   encoder1_c<k>   an encoder's angle error (graduation and interpolation, k per revolution), rad; encoder1
//   encoder1_s<k>   reads the main axis, encoder3 the platform; a ripple measured from it inherits it
//   <declared id>   an input ccal does not model ([[inputs]]), with its sensitivity on each coefficient
// Their parameter codes lie above every layout index and every rate-noise code (kChainParameterBase), so that
// a Tolerance names a chain input as it names a centrifuge error.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ccal {

enum class ChainKind { gravity, time_base, output_gain, output_offset, fixed_term, encoder, declared };

// Parameter code of a chain input: kChainParameterBase + kind·kChainKindStride + index, where index is the
// fixed term's position in all_term_ids(), the encoder's (drive·2 + is_sine)·(kMaxHarmonicOrder+1) + k, or the
// declared input's position in MeasuringChain::declared.
inline constexpr int kChainParameterBase = 1 << 24;
inline constexpr int kChainKindStride = 1 << 16;

struct ChainInput {
  ChainKind kind = ChainKind::gravity;
  int index = 0;
};
int chain_parameter(ChainInput input);
bool is_chain_parameter(int parameter) noexcept;
ChainInput chain_input(int parameter);  // of a chain parameter code (std::invalid_argument otherwise)

// An encoder's angle error term: drive 1 (main axis) or 3 (platform), harmonic k ≥ 1, cos or sin.
struct EncoderTerm {
  int drive = 1;
  int harmonic = 1;
  bool is_sine = false;
};
int encoder_index(EncoderTerm term);
EncoderTerm encoder_term(int index);

// An input ccal does not model ([[inputs]]): it moves the instrument's true coefficients by
// sensitivity · x (e.g. the instrument's temperature within 0.05 K times its K0 temperature coefficient).
struct DeclaredInput {
  std::string id;
  std::string description;
  std::string unit;  // the input's own unit as written (any text, e.g. "K"); values are in it
  std::vector<std::pair<std::string, double>> sensitivity;  // term id → coefficient SI per one unit
};

// What the measuring chain is and what a test measured with it.
struct MeasuringChain {
  std::vector<DeclaredInput> declared;
  // Set where a test measured a drive's rate or ripple from its encoder (docs/model.md §13.1): the time base
  // then acts on that rate, and that encoder's error on that ripple.
  bool main_rate_measured = false, platform_rate_measured = false;
  bool main_ripple_measured = false, platform_ripple_measured = false;
  // Errors of the simulated machine's chain (truth minus the lab's value, SI; a truth file's [errors]).
  std::vector<std::pair<int, double>> errors;
  double error(int parameter) const;  // 0 unless set
};

// The id of a chain input ("g", "time_base", "K1", "encoder3_s2", a declared id).
std::string chain_input_id(int parameter, const MeasuringChain& chain);
// What it is, in words.
std::string chain_input_name(int parameter, const MeasuringChain& chain);
// The code of an id, if it names a chain input: fixed terms must be among `fixed_terms`, encoder harmonics at
// most `harmonic_order`; nullopt for an id that is no chain input at all.
std::optional<int> find_chain_input(std::string_view id, const MeasuringChain& chain,
                                    const std::vector<std::string>& fixed_terms, int harmonic_order);
// The ids of the chain's inputs with a name of their own (g, time_base, output_gain, output_offset), the fixed
// terms and the declared inputs: for the nearest-id hint of a message.
std::vector<std::string> chain_input_ids(const MeasuringChain& chain, const std::vector<std::string>& fixed_terms);
// The ids a configuration accepts, for messages.
std::string chain_input_ids_text(const MeasuringChain& chain, const std::vector<std::string>& fixed_terms);

}  // namespace ccal

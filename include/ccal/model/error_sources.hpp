#pragma once
// The catalogue of centrifuge error sources (docs/model.md §3): every static error of the paper's Table 1,
// every dynamic error of its Table 2, and the drive errors. A *channel* is one scalar error function in the
// kinematic chain; a *parameter* is one number the user sets: a static channel has one parameter, a dynamic
// channel has the Fourier coefficients of its joint angle q,
//     value(q) = c0 + Σ_{k=1..N} (ck cos kq + sk sin kq),
// with parameter ids "<channel>_c0", "<channel>_c1", "<channel>_s1", ... Ids are stable: they are used in
// configuration files, output and fits.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ccal {

// Link of the chain an error belongs to (frame i−1 → i, docs/model.md §2).
enum class Link {
  main_sleeve,        // 0 → 1t: installation/levelling of the main-axis sleeve
  main_axis,          // 1t → 1: main axis Rz(θ1), θ1 = Ωt
  horizontal_sleeve,  // 1 → 2t: arm, Trans(R0, 0, 0)
  horizontal_axis,    // 2t → 2: horizontal axis Rx(β)
  azimuth_sleeve,     // 2 → 3t
  azimuth_axis,       // 3t → 3: azimuth axis / platform Rz(γ)
  base_plane,         // 3 → 4: working base plane, Trans(0, 0, L)
  instrument,         // 4 → 5: accelerometer, Trans(0, 0, l)
  drive,              // the speeds, not a pose
};

// What a channel does to its link. Rotations and translations are about/along the axes of the link's parent
// frame, placed on the parent side of the link's joint rotation (docs/model.md §2.2).
enum class ErrorKind {
  rotation_x,
  rotation_y,
  rotation_z,
  translation_x,
  translation_y,
  translation_z,
  arm_stretch,    // ΔR_d = c·θ̇1² along x of the arm (IEEE 836 radius growth), c in m/(rad/s)²
  main_rate,      // Δω: main-axis rate error, θ̇1 = Ω + Δω
  platform_rate,  // ΔΩ: platform rate mismatch, γ̇ = −(Ω + Δω + ΔΩ) on a counter-rotating platform
  // Rate ripple of a drive (docs/model.md §3.1): the drive's rate relative to its nominal rate is
  // 1 + r(q), r(q) = Σ_{k=1..N} (ck cos kq + sk sin kq), a Fourier series in the drive's own nominal angle q
  // (dimensionless, e.g. "10 ppm"); its angle error is the zero-mean integral Σ (ck sin kq − sk cos kq)/k.
  // The c0 slot of these channels is unused (a constant rate error is Δω or ΔΩ).
  main_ripple,      // main axis, q = θ1's nominal angle
  platform_ripple,  // platform (azimuth axis) drive, q = γ's nominal angle; its tracking error when
                    // phase-locked
};

// Joint angle a dynamic channel is a function of.
enum class Joint { none, main, horizontal, azimuth };

// SI unit of a channel's value.
enum class SourceUnit { rad, m, rad_per_s, m_per_rad_per_s_squared, relative };
std::string_view unit_symbol(SourceUnit unit) noexcept;

struct Channel {
  std::string_view id;
  Link link;
  ErrorKind kind;
  Joint joint;
  std::string_view description;
};

inline constexpr int kStaticChannelCount = 18;
inline constexpr int kDynamicChannelCount = 17;
inline constexpr int kChannelCount = kStaticChannelCount + kDynamicChannelCount;

// Index of each channel in `channels()`; static channels first. In a namespace of their own (ch::dOmega), so
// that 35 short names, two of which differ only in case (domega, dOmega), stay out of namespace ccal; an
// unscoped enumeration within it, so that an index is an int for the arrays it indexes.
namespace ch {
enum Index : int {
  dthx1t,
  dthy1t,
  dR_s,
  dy2t,
  dthy2t,
  dy3t,
  dthx3t,
  dthy3t,
  dthx4,
  dthy4,
  dx5,
  dy5,
  dthx5,
  dthy5,
  dthz5,
  arm_stretch,
  domega,
  dOmega,
  dx1,
  dy1,
  dz1,
  dthx1,
  dthy1,
  dx2,
  dy2,
  dz2,
  dthy2,
  dthz2,
  dx3,
  dy3,
  dz3,
  dthx3,
  dthy3,
  ripple1,  // main-axis rate ripple
  ripple3,  // platform rate ripple
};
}  // namespace ch
using ChannelIndex = ch::Index;

const std::array<Channel, kChannelCount>& channels() noexcept;
SourceUnit channel_unit(const Channel& channel) noexcept;
std::optional<int> find_channel(std::string_view id) noexcept;

// The highest harmonic order N an ErrorLayout (and [centrifuge] harmonic_order) accepts.
inline constexpr int kMaxHarmonicOrder = 16;

// Where each parameter lives in the flat error vector, for a given maximum harmonic order N of the dynamic
// channels: static channels at 0..17, then per dynamic channel c0, c1, s1, …, cN, sN (2N+1 values).
// Throws std::invalid_argument for N outside 0..kMaxHarmonicOrder.
class ErrorLayout {
 public:
  explicit ErrorLayout(int harmonic_order = 1);
  int harmonic_order() const noexcept { return order_; }
  int size() const noexcept { return kStaticChannelCount + kDynamicChannelCount * (2 * order_ + 1); }
  int static_index(int channel) const noexcept { return channel; }
  // Index of the cos (is_sine = false) or sin coefficient of harmonic k of a dynamic channel.
  int harmonic_index(int channel, int k, bool is_sine) const noexcept {
    const int base = kStaticChannelCount + (channel - kStaticChannelCount) * (2 * order_ + 1);
    return k == 0 ? base : base + 2 * k - 1 + (is_sine ? 1 : 0);
  }
  std::string parameter_id(int index) const;
  // What a parameter is, in words: its channel's description, and for a dynamic one the harmonic, e.g.
  // "azimuth-axis wobble about y3t, cos gamma" for dthy3_c1.
  std::string parameter_name(int index) const;
  // Channel of a parameter, and its harmonic (k, is_sine) for dynamic ones.
  int parameter_channel(int index) const noexcept;
  int parameter_harmonic(int index) const noexcept;
  bool parameter_is_sine(int index) const noexcept;
  SourceUnit parameter_unit(int index) const noexcept;
  std::optional<int> find_parameter(std::string_view id) const;
  std::vector<std::string> parameter_ids() const;

 private:
  int order_;
};

}  // namespace ccal

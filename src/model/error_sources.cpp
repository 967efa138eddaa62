#include "ccal/model/error_sources.hpp"

#include <charconv>
#include <stdexcept>

namespace ccal {

namespace {
using enum Link;
using enum ErrorKind;
using J = Joint;

constexpr std::array<Channel, kChannelCount> kChannels{{
    {"dthx1t", main_sleeve, rotation_x, J::none, "main-axis sleeve levelling about x0"},
    {"dthy1t", main_sleeve, rotation_y, J::none, "main-axis sleeve levelling about y0"},
    {"dR_s", horizontal_sleeve, translation_x, J::none, "radius static error"},
    {"dy2t", horizontal_sleeve, translation_y, J::none, "intersection of horizontal and main axes"},
    {"dthy2t", horizontal_sleeve, rotation_y, J::none, "perpendicularity of horizontal axis to main axis"},
    {"dy3t", azimuth_sleeve, translation_y, J::none, "intersection of azimuth and horizontal axes"},
    {"dthx3t", azimuth_sleeve, rotation_x, J::none, "azimuth sleeve zero error about x2"},
    {"dthy3t", azimuth_sleeve, rotation_y, J::none, "perpendicularity of azimuth axis to horizontal axis"},
    {"dthx4", base_plane, rotation_x, J::none, "working base plane tilt about x3"},
    {"dthy4", base_plane, rotation_y, J::none, "working base plane tilt about y3"},
    {"dx5", instrument, translation_x, J::none, "instrument eccentricity along x4"},
    {"dy5", instrument, translation_y, J::none, "instrument eccentricity along y4"},
    {"dthx5", instrument, rotation_x, J::none, "instrument mounting tilt about x4"},
    {"dthy5", instrument, rotation_y, J::none, "instrument mounting tilt about y4"},
    {"dthz5", instrument, rotation_z, J::none, "instrument azimuth (IA) zero error"},
    {"arm_stretch", horizontal_sleeve, ErrorKind::arm_stretch, J::none, "arm stretch c, dR_d = c*Omega^2"},
    {"domega", drive, main_rate, J::none, "main-axis rate error"},
    {"dOmega", drive, platform_rate, J::none, "counter-rotating platform rate mismatch"},
    {"dx1", main_axis, translation_x, J::main, "main-axis radial runout along x1t"},
    {"dy1", main_axis, translation_y, J::main, "main-axis radial runout along y1t"},
    {"dz1", main_axis, translation_z, J::main, "main-axis axial float"},
    {"dthx1", main_axis, rotation_x, J::main, "main-axis wobble about x1t"},
    {"dthy1", main_axis, rotation_y, J::main, "main-axis wobble about y1t"},
    {"dx2", horizontal_axis, translation_x, J::horizontal, "horizontal-axis axial float (dynamic radius)"},
    {"dy2", horizontal_axis, translation_y, J::horizontal, "horizontal-axis runout along y2t"},
    {"dz2", horizontal_axis, translation_z, J::horizontal, "horizontal-axis runout along z2t"},
    {"dthy2", horizontal_axis, rotation_y, J::horizontal, "horizontal-axis wobble about y2t"},
    {"dthz2", horizontal_axis, rotation_z, J::horizontal, "horizontal-axis wobble about z2t"},
    {"dx3", azimuth_axis, translation_x, J::azimuth, "azimuth-axis runout along x3t"},
    {"dy3", azimuth_axis, translation_y, J::azimuth, "azimuth-axis runout along y3t"},
    {"dz3", azimuth_axis, translation_z, J::azimuth, "azimuth-axis axial float"},
    {"dthx3", azimuth_axis, rotation_x, J::azimuth, "azimuth-axis wobble about x3t"},
    {"dthy3", azimuth_axis, rotation_y, J::azimuth, "azimuth-axis wobble about y3t"},
    {"ripple1", drive, main_ripple, J::main, "main-axis rate ripple (relative to the rate)"},
    {"ripple3", drive, platform_ripple, J::azimuth, "platform rate ripple (relative to its rate)"},
}};
}  // namespace

std::string_view unit_symbol(SourceUnit unit) noexcept {
  switch (unit) {
    case SourceUnit::rad:
      return "rad";
    case SourceUnit::m:
      return "m";
    case SourceUnit::rad_per_s:
      return "rad/s";
    case SourceUnit::m_per_rad_per_s_squared:
      return "m/(rad/s)^2";
    case SourceUnit::relative:
      return "1";
  }
  return "";
}

const std::array<Channel, kChannelCount>& channels() noexcept { return kChannels; }

SourceUnit channel_unit(const Channel& channel) noexcept {
  switch (channel.kind) {
    case rotation_x:
    case rotation_y:
    case rotation_z:
      return SourceUnit::rad;
    case translation_x:
    case translation_y:
    case translation_z:
      return SourceUnit::m;
    case ErrorKind::arm_stretch:
      return SourceUnit::m_per_rad_per_s_squared;
    case main_rate:
    case platform_rate:
      return SourceUnit::rad_per_s;
    case main_ripple:
    case platform_ripple:
      return SourceUnit::relative;
  }
  return SourceUnit::rad;
}

std::optional<int> find_channel(std::string_view id) noexcept {
  for (int i = 0; i < kChannelCount; ++i)
    if (kChannels[i].id == id) return i;
  return std::nullopt;
}

ErrorLayout::ErrorLayout(int harmonic_order) : order_(harmonic_order) {
  if (harmonic_order < 0 || harmonic_order > kMaxHarmonicOrder)
    throw std::invalid_argument("harmonic order must be between 0 and " + std::to_string(kMaxHarmonicOrder) +
                                ", got " + std::to_string(harmonic_order));
}

int ErrorLayout::parameter_channel(int index) const noexcept {
  if (index < kStaticChannelCount) return index;
  return kStaticChannelCount + (index - kStaticChannelCount) / (2 * order_ + 1);
}

int ErrorLayout::parameter_harmonic(int index) const noexcept {
  if (index < kStaticChannelCount) return 0;
  const int slot = (index - kStaticChannelCount) % (2 * order_ + 1);
  return (slot + 1) / 2;
}

bool ErrorLayout::parameter_is_sine(int index) const noexcept {
  if (index < kStaticChannelCount) return false;
  const int slot = (index - kStaticChannelCount) % (2 * order_ + 1);
  return slot > 0 && slot % 2 == 0;
}

SourceUnit ErrorLayout::parameter_unit(int index) const noexcept {
  return channel_unit(kChannels[parameter_channel(index)]);
}

std::string ErrorLayout::parameter_id(int index) const {
  const Channel& c = kChannels[parameter_channel(index)];
  if (c.joint == Joint::none) return std::string(c.id);
  return std::string(c.id) + (parameter_is_sine(index) ? "_s" : "_c") +
         std::to_string(parameter_harmonic(index));
}

std::string ErrorLayout::parameter_name(int index) const {
  const Channel& c = kChannels[parameter_channel(index)];
  if (c.joint == Joint::none) return std::string(c.description);
  const int k = parameter_harmonic(index);
  const std::string_view angle = c.joint == Joint::main         ? "theta1"
                                 : c.joint == Joint::horizontal ? "beta"
                                                                : "gamma";
  if (k == 0) return std::string(c.description) + ", constant";
  return std::string(c.description) + (parameter_is_sine(index) ? ", sin " : ", cos ") +
         (k == 1 ? "" : std::to_string(k) + " ") + std::string(angle);
}

std::optional<int> ErrorLayout::find_parameter(std::string_view id) const {
  if (auto c = find_channel(id); c && kChannels[*c].joint == Joint::none) return *c;
  const auto underscore = id.rfind('_');
  if (underscore == std::string_view::npos || underscore + 2 > id.size()) return std::nullopt;
  const auto channel = find_channel(id.substr(0, underscore));
  if (!channel || kChannels[*channel].joint == Joint::none) return std::nullopt;
  const char kind = id[underscore + 1];
  if (kind != 'c' && kind != 's') return std::nullopt;
  int k = -1;
  const auto digits = id.substr(underscore + 2);
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
  if (ec != std::errc{} || end != digits.data() + digits.size() || k < 0 || k > order_) return std::nullopt;
  if (kind == 's' && k == 0) return std::nullopt;  // sin(0·q) = 0 has no coefficient
  return harmonic_index(*channel, k, kind == 's');
}

std::vector<std::string> ErrorLayout::parameter_ids() const {
  std::vector<std::string> ids;
  ids.reserve(size());
  for (int i = 0; i < size(); ++i) ids.push_back(parameter_id(i));
  return ids;
}

}  // namespace ccal

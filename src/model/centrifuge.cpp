#include "ccal/model/centrifuge.hpp"

#include <stdexcept>
#include <string>

namespace ccal {

namespace {
int index_or_throw(const ErrorLayout& layout, std::string_view id) {
  if (auto i = layout.find_parameter(id)) return *i;
  throw std::out_of_range("unknown error parameter '" + std::string(id) + "' (harmonic order " +
                          std::to_string(layout.harmonic_order()) + ")");
}
}  // namespace

double CentrifugeModel::error(std::string_view id) const { return errors[index_or_throw(layout, id)]; }

}  // namespace ccal

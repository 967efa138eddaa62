#pragma once
// The reports of `ccal allocate` (docs/cli.md): text with a ready-to-paste [tolerances] section, JSON, CSV.
#include <cstddef>
#include <string>

#include "ccal/verbs/allocate.hpp"

namespace ccal::render {

// How the text is laid out; the defaults are those of `ccal allocate` writing to a file or a pipe.
struct AllocateTextOptions {
  std::size_t width = 100;  // no line wider than this (displayed characters), where a name can give way
  bool wide = false;        // uncut names, the cost column, no width limit
};

// The unit a source's tolerance is shown in: the one the configuration wrote it in, else the bundled
// example's for its kind (angles in rad, lengths in µm, relative errors in ppm).
std::string tolerance_display_unit(const Config& config, int parameter);

std::string text(const verbs::AllocateResult& result, const AllocateTextOptions& options = {});
std::string json(const verbs::AllocateResult& result);
std::string csv(const verbs::AllocateResult& result);

}  // namespace ccal::render

#pragma once
// The reports of `ccal allocate` (docs/cli.md): text with a ready-to-paste [tolerances] section, JSON, CSV.
#include <string>

#include "ccal/verbs/allocate.hpp"

namespace ccal::render {

std::string text(const verbs::AllocateResult& result);
std::string json(const verbs::AllocateResult& result);
std::string csv(const verbs::AllocateResult& result);

}  // namespace ccal::render

#pragma once
// The reports of `ccal identify` (docs/cli.md): text and JSON.
#include <string>

#include "ccal/verbs/identify.hpp"

namespace ccal::render {

std::string text(const verbs::IdentifyResult& result);
std::string json(const verbs::IdentifyResult& result);

}  // namespace ccal::render

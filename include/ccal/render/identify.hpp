#pragma once
// The reports of `ccal identify` (docs/cli.md): text, JSON and CSV (one row per free term).
#include <string>

#include "ccal/verbs/identify.hpp"

namespace ccal::render {

std::string text(const verbs::IdentifyResult& result);
std::string json(const verbs::IdentifyResult& result);
std::string csv(const verbs::IdentifyResult& result);

}  // namespace ccal::render

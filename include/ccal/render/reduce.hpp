#pragma once
// The reports of `ccal reduce` (docs/cli.md): text, JSON, and CSV (the observations file).
#include <string>

#include "ccal/verbs/reduce.hpp"

namespace ccal::render {

std::string text(const verbs::ReduceResult& result);
std::string json(const verbs::ReduceResult& result);
std::string csv(const verbs::ReduceResult& result);

}  // namespace ccal::render

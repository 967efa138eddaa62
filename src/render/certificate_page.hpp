#pragma once
// The calibration certificate as a page of its own (certificate_page.cpp), private to the library: report.cpp
// gives it for observations with a [certificate] table unless the engineering report is asked for.
#include <string>

#include "ccal/render/report.hpp"

namespace ccal::render {

// r must have observations and a [certificate] table; p its provenance (report_commands filled).
std::string certificate_page(const verbs::ReportResult& r, const ReportProvenance& p);

}  // namespace ccal::render

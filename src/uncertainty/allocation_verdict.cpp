// The words of a verification's verdict.
#include "ccal/uncertainty/allocate.hpp"

namespace ccal {

std::string_view verdict_name(Verdict v) noexcept {
  switch (v) {
    case Verdict::not_checked:
      return "not checked";
    case Verdict::pass:
      return "pass";
    case Verdict::pass_within_sampling:
      return "pass within sampling";
    case Verdict::fail:
      return "fail";
  }
  return "";
}

}  // namespace ccal

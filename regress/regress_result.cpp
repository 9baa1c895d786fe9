#include "regress/regress_result.h"

namespace vesper::regress {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Pass:
      return "pass";
    case Verdict::Regressed:
      return "regressed";
    case Verdict::Error:
      return "error";
  }
  return "error";
}

std::optional<Verdict> parse_verdict(std::string_view name) {
  for (Verdict v : {Verdict::Pass, Verdict::Regressed, Verdict::Error})
    if (name == verdict_name(v)) return v;
  return std::nullopt;
}

}  // namespace vesper::regress

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

}  // namespace vesper::regress

#include "server/locked_store.h"

#include <string>

#include "server/api_error.h"

namespace vesper {

JobSummary require_job(const JobStore& store, int64_t id) {
  auto j = store.job(id);
  if (!j) throw ApiError(404, "no job " + std::to_string(id));
  return *j;
}

}  // namespace vesper

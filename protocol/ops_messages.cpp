#include "protocol/ops_messages.h"

#include "protocol/fields.h"
#include "protocol/json_fields.h"

namespace vesper::protocol {

namespace f = field;
using detail::required;

VESPER_JSON_FIELDS(DeleteJobResponse, required(f::kDeleted, &DeleteJobResponse::deleted),
                   required(f::kBlobsFreed, &DeleteJobResponse::blobs_freed),
                   required(f::kBytesFreed, &DeleteJobResponse::bytes_freed))
VESPER_JSON_FIELDS(GoodbyeRequest, required(f::kWorkerId, &GoodbyeRequest::worker_id))
VESPER_JSON_FIELDS(PruneResponse, required(f::kPruned, &PruneResponse::pruned))

}  // namespace vesper::protocol

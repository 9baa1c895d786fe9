#include "protocol/error_body.h"

#include "protocol/fields.h"
#include "protocol/json_fields.h"

namespace vesper::protocol {

VESPER_JSON_FIELDS(ErrorBody, detail::required(field::kError, &ErrorBody::error),
                   detail::optional(field::kPath, &ErrorBody::path))

}  // namespace vesper::protocol

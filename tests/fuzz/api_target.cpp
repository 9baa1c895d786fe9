// Fuzz target: the farm API's request bodies. Every input goes to each of
// the server's readers (server/requests.h: submit, register, lease,
// heartbeat, complete, fail), whose documented error is ApiError (a 400), to
// the scan of a submitted scene for files outside its directory
// (jobs/scene_references.h, after parse_json: JsonError), and to the
// protocol library's from_json of every request message, whose documented
// error is nlohmann::json::exception (after parse_json: JsonError).
#include "common/json_error.h"
#include "common/json_parse.h"
#include "jobs/scene_references.h"
#include "protocol/job_messages.h"
#include "protocol/worker_messages.h"
#include "server/api_error.h"
#include "server/requests.h"
#include "tests/fuzz/fuzz_target.h"

namespace vesper::fuzz {
namespace {

template <class Read>
bool server_reads(const std::string& body, Read read) {
  try {
    read(body);
    return true;
  } catch (const ApiError& e) {
    if (e.status() != 400) finding("a request body was answered " + std::to_string(e.status()));
    return false;
  }
}

template <class Message>
bool protocol_reads(const nlohmann::json& doc) {
  try {
    (void)doc.get<Message>();
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

}  // namespace
}  // namespace vesper::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  using fuzz::server_reads;
  const std::string body = fuzz::text_of(data, size);
  bool accepted = server_reads(body, [](const std::string& b) {
    const JobSpec spec = read_job_request(b);
    if (task_count(spec) < 1) fuzz::finding("an accepted submit makes no task");
  });
  accepted |= server_reads(body, read_register_request);
  accepted |= server_reads(body, read_lease_request);
  accepted |= server_reads(body, read_heartbeat_request);
  accepted |= server_reads(body, read_complete_request);
  accepted |= server_reads(body, read_fail_request);
  nlohmann::json doc;
  try {
    doc = parse_json(body, "request body");
  } catch (const JsonError&) {
    if (accepted) fuzz::finding("a reader accepted a body that parse_json refuses");
    return 0;
  }
  (void)outside_reference(doc);
  namespace p = protocol;
  fuzz::protocol_reads<p::SubmitRequest>(doc);
  fuzz::protocol_reads<p::RegisterRequest>(doc);
  fuzz::protocol_reads<p::LeaseRequest>(doc);
  fuzz::protocol_reads<p::HeartbeatRequest>(doc);
  fuzz::protocol_reads<p::CompleteRequest>(doc);
  fuzz::protocol_reads<p::FailRequest>(doc);
  if (accepted) fuzz::note_accepted();
  return 0;
}

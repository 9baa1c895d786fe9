// docs/api/openapi.yaml and the route table the server registers its
// handlers from (protocol/routes.h) list the same endpoints, methods and
// tokens. The document is read as a tree of keys with the subset of YAML its
// header describes (no YAML library).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "protocol/job_messages.h"
#include "protocol/ops_messages.h"
#include "protocol/routes.h"
#include "protocol/worker_messages.h"

namespace vesper::protocol {
namespace {

// A YAML block mapping reduced to its keys (values are not kept). Items of a
// block list that are mappings add their keys to the list's key, so
// `security: [- submitterToken: [], - workerToken: []]` has two children.
struct KeyTree {
  std::map<std::string, std::unique_ptr<KeyTree>> children;
  const KeyTree* child(const std::string& key) const {
    auto it = children.find(key);
    return it == children.end() ? nullptr : it->second.get();
  }
  KeyTree& add(const std::string& key) {
    auto& c = children[key];
    if (!c) c = std::make_unique<KeyTree>();
    return *c;
  }
};

std::string unquote(std::string s) {
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front())
    return s.substr(1, s.size() - 2);
  return s;
}

// Reads the keys of the subset described at the top of openapi.yaml.
KeyTree read_key_tree(std::istream& in) {
  KeyTree root;
  std::vector<std::pair<int, KeyTree*>> stack{{-1, &root}};  // (indent, node)
  int block_scalar_indent = -1;  // inside `key: |` text deeper than this
  std::string line;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] == '#') continue;
    int indent = int(first);
    if (block_scalar_indent >= 0 && indent > block_scalar_indent) continue;
    block_scalar_indent = -1;
    std::string text = line.substr(first);
    if (text.rfind("- ", 0) == 0) {  // a list item: its key sits two columns in
      text = text.substr(2);
      indent += 2;
    }
    const size_t colon = text.find(": ");
    const bool ends_with_colon = !text.empty() && text.back() == ':';
    if (colon == std::string::npos && !ends_with_colon) continue;  // a scalar list item
    const std::string key = unquote(
        text.substr(0, ends_with_colon && colon == std::string::npos ? text.size() - 1 : colon));
    const std::string value = colon == std::string::npos ? "" : text.substr(colon + 2);
    while (stack.back().first >= indent) stack.pop_back();
    KeyTree& node = stack.back().second->add(key);
    if (value.empty())
      stack.emplace_back(indent, &node);
    else if (value[0] == '|' || value[0] == '>')
      block_scalar_indent = indent;
  }
  return root;
}

KeyTree load_openapi() {
  std::ifstream in(VESPER_SOURCE_DIR "/docs/api/openapi.yaml");
  EXPECT_TRUE(in) << "cannot read docs/api/openapi.yaml";
  return read_key_tree(in);
}

// The token an operation's `security` asks for.
std::string role_of(const KeyTree& operation) {
  const KeyTree* security = operation.child("security");
  if (!security) return "(no security: every operation must state one)";
  const bool sub = security->child("submitterToken"), wrk = security->child("workerToken");
  if (security->children.size() != size_t(sub) + size_t(wrk)) return "(unknown scheme)";
  return std::string(to_string(sub && wrk ? Role::Either
                               : sub      ? Role::Submitter
                               : wrk      ? Role::Worker
                                          : Role::None));
}

// "METHOD path" -> role.
using Endpoints = std::map<std::string, std::string>;

Endpoints documented(const KeyTree& doc) {
  static const std::set<std::string> methods{"get",     "put",  "post",  "delete",
                                             "options", "head", "patch", "trace"};
  Endpoints out;
  const KeyTree* paths = doc.child("paths");
  if (!paths) return out;
  for (const auto& [path, item] : paths->children)
    for (const auto& [key, operation] : item->children)
      if (methods.count(key)) {
        std::string method = key;
        for (char& c : method) c = char(std::toupper(static_cast<unsigned char>(c)));
        out[method + " " + path] = role_of(*operation);
      }
  return out;
}

Endpoints routed() {
  Endpoints out;
  for (const Route& r : kRoutes)
    out[std::string(to_string(r.method)) + " " + full_path(r)] = std::string(to_string(r.role));
  return out;
}

TEST(OpenApiTest, TheDocumentAndTheRouteTableListTheSameEndpointsAndTokens) {
  const Endpoints doc = documented(load_openapi());
  const Endpoints table = routed();
  ASSERT_FALSE(doc.empty());
  for (const auto& [endpoint, role] : table) {
    auto it = doc.find(endpoint);
    if (it == doc.end())
      ADD_FAILURE() << endpoint << " is routed but not in docs/api/openapi.yaml";
    else
      EXPECT_EQ(it->second, role) << endpoint << ": the token in openapi.yaml differs";
  }
  for (const auto& [endpoint, role] : doc)
    EXPECT_TRUE(table.count(endpoint)) << endpoint << " is documented but not routed";
}

TEST(OpenApiTest, EveryRouteIsDistinct) {
  std::set<std::string> seen;
  for (const Route& r : kRoutes)
    EXPECT_TRUE(seen.insert(std::string(to_string(r.method)) + " " + full_path(r)).second)
        << full_path(r);
}

TEST(OpenApiTest, HeadRoutesHaveAGetRouteOfTheSamePath) {
  for (const Route& h : kRoutes) {
    if (h.method != Method::Head) continue;
    bool found = false;
    for (const Route& g : kRoutes)
      found = found || (g.method == Method::Get && full_path(g) == full_path(h) &&
                        g.endpoint == h.endpoint && g.role == h.role);
    EXPECT_TRUE(found) << full_path(h);
  }
}

// The property names of components/schemas/<name> (for an allOf, those of
// its inline parts; `also` adds a referenced schema's).
std::set<std::string> properties(const KeyTree& doc, const std::string& name,
                                 const std::string& also = "") {
  std::set<std::string> out;
  const KeyTree* schemas =
      doc.child("components") ? doc.child("components")->child("schemas") : nullptr;
  const KeyTree* schema = schemas ? schemas->child(name) : nullptr;
  if (!schema) return out;
  if (const KeyTree* all = schema->child("allOf")) schema = all;
  if (const KeyTree* props = schema->child("properties"))
    for (const auto& [key, value] : props->children) out.insert(key);
  if (!also.empty())
    for (const std::string& key : properties(doc, also)) out.insert(key);
  return out;
}

std::set<std::string> keys_of(const nlohmann::json& j) {
  std::set<std::string> out;
  for (const auto& [key, value] : j.items()) out.insert(key);
  return out;
}

// Every message with every optional field set writes exactly the properties
// its schema documents: a field added to a message and not to openapi.yaml
// (or the other way round) fails here.
TEST(OpenApiTest, EveryMessageWritesTheKeysItsSchemaDocuments) {
  const KeyTree doc = load_openapi();
  SubmitRequest submit;
  submit.assets = {{"a.obj", "B"}};
  submit.noise_target = 0.01;
  submit.min_spp = submit.max_spp = 8;
  submit.time_limit = 60;
  submit.aovs = {"variance"};
  submit.layer_variance = true;
  submit.seed = 7;
  submit.scale = 0.25;
  submit.half = true;
  submit.task_timeout = 3600;
  EXPECT_EQ(keys_of(nlohmann::json(submit)), properties(doc, "SubmitRequest"));

  LeaseResponse lease;
  lease.noise_target = 0.02;
  lease.min_spp = 8;
  lease.time_limit = 30;
  lease.aovs = {"variance", "albedo"};
  lease.layer_variance = true;
  lease.seed = 7;
  lease.scale = 0.5;
  lease.half = true;
  lease.task_timeout = 3600;
  EXPECT_EQ(keys_of(nlohmann::json(lease)), properties(doc, "LeaseResponse"));
  EXPECT_EQ(keys_of(nlohmann::json(lease.task)), properties(doc, "LeasedTask"));

  const FrameInfo frame{1, FrameState::Ready, 1, 1, "B", "e", 0.01, 40.5, "noise_target"};
  EXPECT_EQ(keys_of(nlohmann::json(frame)), properties(doc, "Frame"));
  const TaskInfo task{1, 1, 1, 0, 8, "done", 1, "w", "R", true, 0.5, 2, 10.0, 12.5, 2.5};
  EXPECT_EQ(keys_of(nlohmann::json(task)), properties(doc, "Task"));
  JobDetail detail;
  detail.summary.submitted = 9;
  detail.summary.started = 10;
  detail.summary.finished = 20;
  detail.summary.eta = 5;
  detail.tasks = {task};
  detail.frames = {frame};
  detail.tasks_next = 1;
  detail.now = 21;
  EXPECT_EQ(keys_of(nlohmann::json(detail)), properties(doc, "JobDetail", "JobSummary"));
  EXPECT_EQ(keys_of(nlohmann::json(detail.summary)), properties(doc, "JobSummary"));
  const JobList list{{detail.summary}, 21};
  EXPECT_EQ(keys_of(nlohmann::json(list)), properties(doc, "JobList"));
  EXPECT_EQ(keys_of(nlohmann::json(CompleteRequest{"L", "R", "log"})),
            properties(doc, "CompleteRequest"));
}

// The housekeeping messages (ops16): a worker with its state, current task
// and blocklist; job deletion; goodbye; prune.
TEST(OpenApiTest, HousekeepingMessagesWriteTheKeysTheirSchemasDocument) {
  const KeyTree doc = load_openapi();
  WorkerInfo worker{"w", "host", 1, 2, 1, "online", WorkerTask{3, 4}, {3}};
  EXPECT_EQ(keys_of(nlohmann::json(worker)), properties(doc, "Worker"));
  EXPECT_EQ(keys_of(nlohmann::json(DeleteJobResponse{1, 2, 3})),
            properties(doc, "DeleteJobResponse"));
  EXPECT_EQ(keys_of(nlohmann::json(GoodbyeRequest{"w"})), properties(doc, "GoodbyeRequest"));
  EXPECT_EQ(keys_of(nlohmann::json(PruneResponse{{"w"}})), properties(doc, "PruneResponse"));
}

TEST(OpenApiTest, TheKeyReaderFollowsIndentationListsAndBlockScalars) {
  std::istringstream in(R"(# comment
a:
  b: 1
  text: |
    not: a key
    - nor: this
  list:
    - x: []
      y: 2
    - z: []
    - scalar item
c: {k: v}
"/quoted/{p}":
  get:
    security: []
)");
  const KeyTree t = read_key_tree(in);
  ASSERT_TRUE(t.child("a"));
  const KeyTree& a = *t.child("a");
  EXPECT_EQ(a.children.size(), 3u);
  EXPECT_TRUE(a.child("text")->children.empty());
  const KeyTree& list = *a.child("list");
  EXPECT_EQ(list.children.size(), 3u);
  EXPECT_TRUE(list.child("x") && list.child("y") && list.child("z"));
  EXPECT_TRUE(t.child("c") && t.child("c")->children.empty());
  ASSERT_TRUE(t.child("/quoted/{p}"));
  EXPECT_EQ(role_of(*t.child("/quoted/{p}")->child("get")), "none");
}

}  // namespace
}  // namespace vesper::protocol

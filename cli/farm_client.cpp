#include "cli/farm_client.h"

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "cli/local_server.h"
#include "common/sha256.h"
#include "protocol/error_body.h"
#include "protocol/fields.h"
#include "protocol/paths.h"
#include "worker/http_client.h"

namespace vesper::cli {
namespace {

std::string describe(const std::string& what, const worker_detail::HttpResponse& r) {
  if (r.status == 0) return what + ": cannot reach the server: " + r.error;
  std::string msg = what + ": HTTP " + std::to_string(r.status);
  protocol::ErrorBody error;
  try {
    error = nlohmann::json::parse(r.body).get<protocol::ErrorBody>();
  } catch (const nlohmann::json::exception&) {
    // Not the server's error body (a proxy's page?): show its start.
    return r.body.empty() ? msg : msg + ": " + r.body.substr(0, 300);
  }
  msg += ": " + error.error;
  if (!error.path.empty()) msg += " (at " + error.path + ")";
  return msg;
}

nlohmann::json parse_answer(const std::string& what, const worker_detail::HttpResponse& r) {
  if (!r.ok()) throw FarmClientError(describe(what, r));
  if (r.body.empty()) return nlohmann::json::object();
  auto doc = nlohmann::json::parse(r.body, nullptr, false);
  if (doc.is_discarded()) throw FarmClientError(what + ": the server's answer is not JSON");
  return doc;
}

const char* env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}

}  // namespace

std::string resolve_server_url(const FarmSettings& settings,
                               const std::optional<std::string>& url) {
  if (url) return *url;
  if (const char* v = env("VESPER_SERVER")) return v;
  return settings.worker.server;
}

std::string resolve_token(const FarmSettings& settings, const std::string& server_url,
                          const std::optional<std::string>& token, TokenRole role) {
  if (token) return *token;
  const char* var = role == TokenRole::Submitter ? "VESPER_TOKEN" : "VESPER_WORKER_TOKEN";
  if (const char* v = env(var)) return v;
  const std::filesystem::path file =
      local_server_data_dir(server_url).value_or(expand_user(settings.server.data_dir)) /
      "tokens.json";
  const char* key = role == TokenRole::Submitter ? "submitter" : "worker";
  std::ifstream in(file);
  const bool readable = bool(in);
  const auto doc = nlohmann::json::parse(in, nullptr, false);
  if (!readable || doc.is_discarded() || !doc.contains(key) || !doc[key].is_string())
    throw FarmClientError(std::string("no ") + key + " token: pass --token, set " + var +
                          ", or run on the server's machine (looked for " + file.string() + ": " +
                          (readable ? "no \"" + std::string(key) + "\" in it" : "not readable") +
                          ")");
  return doc[key].get<std::string>();
}

FarmClient::FarmClient(std::string url, std::string token)
    : url_(std::move(url)), http_(std::make_unique<worker_detail::HttpClient>(url_, token)) {}

FarmClient::~FarmClient() = default;

nlohmann::json FarmClient::get_job_json(int64_t job) {
  nlohmann::json all = get_json(protocol::job_path(job));
  // A task page may be followed by more. Each page lists the frames of its
  // tasks (a frame split over two pages is in both: the later one is kept);
  // the summary of the first page stands for the whole.
  for (auto next = all.find(protocol::field::kTasksNext); next != all.end();
       next = all.find(protocol::field::kTasksNext)) {
    const auto after = next->get<int64_t>();
    all.erase(next);
    nlohmann::json page =
        get_json(protocol::job_path(job) + "?" + std::string(protocol::kTasksAfterParam) + "=" +
                 std::to_string(after));
    auto& tasks = all[protocol::field::kTasks];
    for (auto& t : page[protocol::field::kTasks]) tasks.push_back(std::move(t));
    auto& frames = all[protocol::field::kFrames];
    for (auto& f : page[protocol::field::kFrames]) {
      if (!frames.empty() &&
          frames.back().at(protocol::field::kFrame) == f.at(protocol::field::kFrame))
        frames.back() = std::move(f);
      else
        frames.push_back(std::move(f));
    }
    if (page.contains(protocol::field::kTasksNext))
      all[protocol::field::kTasksNext] = page[protocol::field::kTasksNext];
  }
  return all;
}

protocol::JobDetail FarmClient::get_job(int64_t job) {
  return get_job_json(job).get<protocol::JobDetail>();
}

nlohmann::json FarmClient::get_json(const std::string& path) {
  return parse_answer("GET " + path, http_->get(protocol::api(path)));
}

nlohmann::json FarmClient::post_json(const std::string& path, const nlohmann::json& body) {
  return parse_answer("POST " + path, http_->post_json(protocol::api(path), body.dump()));
}

nlohmann::json FarmClient::delete_json(const std::string& path) {
  return parse_answer("DELETE " + path, http_->del(protocol::api(path)));
}

std::string FarmClient::get_text(const std::string& path) {
  const auto r = http_->get(protocol::api(path));
  if (!r.ok()) throw FarmClientError(describe("GET " + path, r));
  return r.body;
}

std::string FarmClient::put_blob(const std::filesystem::path& file) {
  const auto sha = sha256_file(file);
  if (!sha) throw FarmClientError(file.string() + ": cannot read");
  // Content-addressed: a blob the server has is not sent again.
  const std::string blob = protocol::api(protocol::blob_path(*sha));
  if (http_->head(blob).status == 200) return *sha;
  const auto r = http_->put_file(blob, file);
  if (!r.ok()) throw FarmClientError(describe("upload of " + file.string(), r));
  return *sha;
}

void FarmClient::download(const std::string& path, const std::filesystem::path& file) {
  const std::filesystem::path part = file.string() + ".part";
  auto r = http_->get_to_file(protocol::api(path), part);
  if (!r.ok()) {
    std::ifstream in(part);  // the error answer went to the file
    r.body.assign(std::istreambuf_iterator<char>(in), {});
    std::error_code ec;
    std::filesystem::remove(part, ec);
    throw FarmClientError(describe("GET " + path, r));
  }
  std::filesystem::rename(part, file);
}

}  // namespace vesper::cli

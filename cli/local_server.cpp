#include "cli/local_server.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

namespace vesper::cli {
namespace fs = std::filesystem;
namespace {

fs::path records_dir() {
  const char* state = std::getenv("XDG_STATE_HOME");
  if (state && *state) return fs::path(state) / "vesper" / "servers";
  const char* home = std::getenv("HOME");
  return fs::path(home && *home ? home : "/tmp") / ".local" / "state" / "vesper" / "servers";
}

// The port of a URL on this machine ("http://127.0.0.1:8765/..." -> 8765);
// nullopt for another host or a URL that is not http(s)://host[:port].
std::optional<int> local_port(const std::string& url) {
  const size_t scheme = url.find("://");
  if (scheme == std::string::npos) return std::nullopt;
  const std::string authority = url.substr(scheme + 3, url.find('/', scheme + 3) - scheme - 3);
  const size_t colon = authority.rfind(':');
  const bool has_port =
      colon != std::string::npos && authority.find(']', colon) == std::string::npos;
  const std::string host = has_port ? authority.substr(0, colon) : authority;
  const bool local = host == "localhost" || host.rfind("127.", 0) == 0 || host == "[::1]" ||
                     host == "0.0.0.0" || host == "[::]";
  if (!local) return std::nullopt;
  if (!has_port) return url.rfind("https", 0) == 0 ? 443 : 80;
  try {
    return std::stoi(authority.substr(colon + 1));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<fs::path> record_file(const std::string& url) {
  const std::optional<int> port = local_port(url);
  if (!port) return std::nullopt;
  return records_dir() / (std::to_string(*port) + ".json");
}

nlohmann::json read_record(const fs::path& file) {
  std::ifstream in(file);
  auto doc = nlohmann::json::parse(in, nullptr, false);
  const bool valid = doc.is_object() && doc.contains("pid") && doc["pid"].is_number_integer() &&
                     doc.contains("data_dir") && doc["data_dir"].is_string();
  return valid ? doc : nlohmann::json();
}

bool process_alive(long long pid) { return ::kill(pid_t(pid), 0) == 0 || errno == EPERM; }

// Records of servers that could not remove theirs (kill -9, a crash).
void remove_dead_records(const fs::path& dir) {
  std::error_code ec, ignored;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".json") continue;  // not a record being written
    const nlohmann::json doc = read_record(it->path());
    if (doc.is_null() || !process_alive(doc["pid"].get<long long>()))
      fs::remove(it->path(), ignored);
  }
}

}  // namespace

void record_local_server(const std::string& url, const fs::path& data_dir) {
  const auto file = record_file(url);
  if (!file) return;
  std::error_code ec;
  fs::create_directories(file->parent_path(), ec);
  remove_dead_records(file->parent_path());
  const fs::path tmp = file->string() + ".tmp-" + std::to_string(::getpid());
  std::ofstream(tmp) << nlohmann::json{{"url", url},
                                       {"data_dir", fs::absolute(data_dir, ec).string()},
                                       {"pid", ::getpid()}}
                            .dump()
                     << "\n";
  fs::rename(tmp, *file, ec);  // best effort: without it, clients need --token
}

void forget_local_server(const std::string& url) {
  const auto file = record_file(url);
  if (!file) return;
  const nlohmann::json doc = read_record(*file);
  std::error_code ec;
  if (!doc.is_null() && doc["pid"].get<long long>() == ::getpid()) fs::remove(*file, ec);
}

std::optional<fs::path> local_server_data_dir(const std::string& url) {
  const auto file = record_file(url);
  if (!file) return std::nullopt;
  const nlohmann::json doc = read_record(*file);
  if (doc.is_null() || !process_alive(doc["pid"].get<long long>())) return std::nullopt;
  return fs::path(doc["data_dir"].get<std::string>());
}

}  // namespace vesper::cli

#pragma once
// Bearer tokens of the farm, kept in <data_dir>/tokens.json:
//   {"submitter": "<hex>", "worker": "<hex>", "shared_worker_enabled": true,
//    "workers": {"<name>": {"token": "<hex>", "enabled": true}, ...}}
// "worker" is the shared worker token (every worker may use it unless
// "shared_worker_enabled" is false); "workers" holds per-worker tokens an
// operator can revoke one by one (`vesper tokens`, cli/tokens_command.cpp).
// The last two keys are optional (older files have neither).
//
// The file is created on first start with mode 0600 (written to a private
// temp file opened O_CREAT|O_EXCL 0600, then hard-linked into place, so it is
// never world-readable and never seen half written) and reused afterwards; a
// token file readable by group or others is refused. Edits are written the
// same way and renamed over it; the server re-reads it when it changes, so a
// revocation takes effect without a restart.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <sys/stat.h>

namespace vesper {

struct WorkerToken {
  std::string token;
  bool enabled = true;
};

struct Tokens {
  std::string submitter;
  std::string worker;  // the shared worker token
  bool shared_worker_enabled = true;
  std::map<std::string, WorkerToken> workers;  // name -> its own token

  // Whether `token` may make worker calls (constant time per comparison).
  bool worker_allowed(const std::string& token) const;
};

Tokens load_or_create_tokens(const std::filesystem::path& file);
// Throws std::runtime_error naming the file and what is wrong.
Tokens read_tokens(const std::filesystem::path& file);
// Replaces the file atomically (0600 temp file, fsync, rename).
void write_tokens(const std::filesystem::path& file, const Tokens& tokens);

// The token file as the server sees it: read (or created) at start, read
// again whenever its inode, size or modification time change (and compared
// byte for byte within a second of a change, file times being coarse). A changed file
// that cannot be read is logged and the previous tokens stay in force.
// Thread safe.
class TokenFile {
 public:
  explicit TokenFile(std::filesystem::path file);
  std::shared_ptr<const Tokens> current();

 private:
  std::filesystem::path file_;
  std::mutex mutex_;
  std::shared_ptr<const Tokens> tokens_;
  std::string text_;  // the bytes tokens_ was read from
  struct stat seen_ {};
};

}  // namespace vesper

#pragma once
// Bearer tokens of the farm: one for submitters, one for workers, kept in
// <data_dir>/tokens.json ({"submitter": "<hex>", "worker": "<hex>"}).
// The file is created on first start with mode 0600 (written to a private
// temp file opened O_CREAT|O_EXCL 0600, then hard-linked into place, so it is
// never world-readable and never seen half written) and reused afterwards; a
// token file readable by group or others is refused.
#include <filesystem>
#include <string>

namespace vesper {

struct Tokens {
  std::string submitter;
  std::string worker;
};

Tokens load_or_create_tokens(const std::filesystem::path& file);

}  // namespace vesper

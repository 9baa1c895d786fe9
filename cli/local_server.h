#pragma once
// Servers running on this machine, so that clients find their token without
// flags: `vesper server` records its URL and data dir (the folder of
// tokens.json) in $XDG_STATE_HOME/vesper/servers/<port>.json (default
// ~/.local/state/...) while it runs, and `vesper status|submit|worker|...`
// talking to a local URL read the token from that data dir. A record whose
// process is gone is ignored.
#include <filesystem>
#include <optional>
#include <string>

namespace vesper::cli {

// Writes the record of this process's server listening at `url`.
void record_local_server(const std::string& url, const std::filesystem::path& data_dir);
// Removes it (if it is still this process's).
void forget_local_server(const std::string& url);
// The data dir of the running server on this machine that `url` reaches
// (host localhost, 127.x, ::1 or 0.0.0.0; same port), if one is recorded.
std::optional<std::filesystem::path> local_server_data_dir(const std::string& url);

}  // namespace vesper::cli

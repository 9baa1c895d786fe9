#pragma once
// The job commands' shared frame (vesper status, cancel, logs, ...): a
// FarmClient from the settings and flags, the farm's errors turned into a
// message and an exit code (2: bad settings, 1: anything else).
#include <spdlog/spdlog.h>

#include <exception>
#include <map>
#include <string>

#include "cli/commands.h"
#include "cli/farm_client.h"
#include "cli/farm_config.h"

namespace vesper::cli {

// worker id -> name, for tables people read (escaped: names come from
// whoever holds a worker token, and an old server did not refuse ESC or CR).
std::map<std::string, std::string> worker_names(FarmClient& c);

template <typename Body>
int with_client(const JobCommandOptions& o, Body&& body) {
  try {
    const FarmSettings settings = load_farm_settings(o.farm.config);
    const std::string url = resolve_server_url(settings, o.farm.server);
    FarmClient client(url, resolve_token(settings, url, o.farm.token, TokenRole::Submitter));
    return body(client);
  } catch (const FarmConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace vesper::cli

#include "bench/farm/monitor_pages.h"

#include <httplib.h>

#include <chrono>
#include <nlohmann/json.hpp>

namespace vesper::farm_bench {

MonitorPages::MonitorPages(int port, std::string submitter_token, int pages, double interval,
                           int64_t job)
    : port_(port),
      token_(std::move(submitter_token)),
      pages_(pages),
      interval_(interval),
      job_(job) {
  for (int i = 0; i < pages; ++i) threads_.emplace_back([this, i] { page(i); });
}

MonitorPages::~MonitorPages() { stop(); }

void MonitorPages::stop() {
  stop_ = true;
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

void MonitorPages::page(int index) {
  httplib::Client c("127.0.0.1", port_);
  c.set_keep_alive(true);  // as a browser keeps its connection
  c.set_read_timeout(60);
  auto login =
      c.Post("/api/v1/login", nlohmann::json{{"token", token_}}.dump(), "application/json");
  if (!login || login->status != 200) {
    ++failures_;
    return;
  }
  const std::string set = login->get_header_value("Set-Cookie");
  const httplib::Headers h{{"Cookie", set.substr(0, set.find(';'))}, {"X-Vesper-Monitor", "1"}};
  const std::string paths[] = {"/api/v1/jobs", "/api/v1/workers",
                               "/api/v1/jobs/" + std::to_string(job_) + "?tasks_limit=500"};
  // Pages opened at different moments: their polls do not line up.
  auto next = std::chrono::steady_clock::now() +
              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                  std::chrono::duration<double>(interval_ * index / double(pages_)));
  while (!stop_) {
    while (!stop_ && std::chrono::steady_clock::now() < next)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (stop_) break;
    for (const std::string& p : paths) {
      auto r = c.Get(p.c_str(), h);
      ++(r && r->status == 200 ? requests_ : failures_);
    }
    // The page polls `interval` after the answers, as monitor.js does.
    next = std::chrono::steady_clock::now() +
           std::chrono::duration_cast<std::chrono::steady_clock::duration>(
               std::chrono::duration<double>(interval_));
  }
}

}  // namespace vesper::farm_bench

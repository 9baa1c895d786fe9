#include "worker/leased_task.h"

namespace vesper::worker_detail {
namespace {

std::string id_string(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>() : v.dump();
}

}  // namespace

LeasedTask parse_lease(const nlohmann::json& j) {
  LeasedTask t;
  t.lease_id = j.at("lease_id").get<std::string>();
  t.scene = j.at("scene").get<std::string>();
  t.spp = j.at("spp").get<int>();
  t.lease_seconds = j.value("lease_seconds", 60.0);
  const nlohmann::json& task = j.at("task");
  t.id = id_string(task.at("id"));
  t.job_id = id_string(task.at("job_id"));
  t.frame = task.value("frame", 0);
  t.attempt = task.value("attempt", 0);
  t.sample_begin = task.value("sample_begin", 0);
  t.sample_end = task.value("sample_end", t.spp);
  if (j.contains("assets"))
    for (const nlohmann::json& a : j.at("assets"))
      t.assets.push_back({a.at("name").get<std::string>(), a.at("blob").get<std::string>()});
  return t;
}

}  // namespace vesper::worker_detail

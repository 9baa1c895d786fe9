#include "common/scene_hash.h"

#include <algorithm>
#include <cstdio>

#include "common/frame_pattern.h"
#include "common/keyframes.h"

namespace vesper {

SceneHash::SceneHash(const nlohmann::json& doc) { add_sized(doc.dump()); }

void SceneHash::add_file(const std::string& bytes) { add_sized(bytes); }

void SceneHash::add_sized(const std::string& s) {
  // Length-prefixed so that concatenations stay distinct.
  const uint64_t n = s.size();
  auto add = [this](const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
  };
  add(&n, sizeof n);
  add(s.data(), s.size());
}

std::string SceneHash::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

std::vector<std::string> hashed_file_references(const nlohmann::json& doc) {
  std::vector<std::string> out;
  auto file_of = [&out](const nlohmann::json& node) {
    if (!node.is_object()) return;
    const auto it = node.find("file");
    if (it != node.end() && it->is_string()) out.push_back(it->get<std::string>());
  };
  if (!doc.is_object()) return out;
  // The loader's order: shapes, lights, then media (nlohmann keeps object
  // keys sorted, so iterating "media" is name order, as the loader does).
  for (const char* list : {"shapes", "lights"}) {
    const auto it = doc.find(list);
    if (it != doc.end() && it->is_array())
      for (const auto& node : *it) file_of(node);
  }
  const auto media = doc.find("media");
  if (media != doc.end() && media->is_object())
    for (const auto& [name, node] : media->items()) file_of(node);
  return out;
}

nlohmann::json frame_document(const nlohmann::json& doc, double frame, const std::string& file) {
  return has_keyframes(doc) ? evaluate_keyframes(doc, frame, file) : doc;
}

std::vector<std::string> frame_file_references(const nlohmann::json& frame_doc, long frame) {
  std::vector<std::string> refs = hashed_file_references(frame_doc);
  for (std::string& ref : refs) ref = frame_path(ref, frame).string();
  return refs;
}

bool is_animated(const nlohmann::json& doc) {
  if (has_keyframes(doc)) return true;
  for (const std::string& ref : hashed_file_references(doc))
    if (has_frame_pattern(ref)) return true;
  return false;
}

namespace {

void collect_key_times(const nlohmann::json& node, std::vector<double>& times, bool& smooth) {
  if (is_keyframed(node)) {
    if (node.value("interp", std::string("linear")) != "linear") smooth = true;
    if (node["keys"].is_array())
      for (const auto& key : node["keys"])
        if (key.is_array() && !key.empty() && key[0].is_number()) times.push_back(key[0]);
  } else if (node.is_structured()) {
    for (const auto& value : node) collect_key_times(value, times, smooth);
  }
}

}  // namespace

nlohmann::json shutter_state(const nlohmann::json& doc, double frame, const std::string& file) {
  if (!has_keyframes(doc)) return nullptr;
  const nlohmann::json at_frame = evaluate_keyframes(doc, frame, file);
  const nlohmann::json* shutter = nullptr;
  if (const auto r = at_frame.find("render"); r != at_frame.end() && r->is_object())
    if (const auto s = r->find("shutter"); s != r->end()) shutter = &*s;
  if (!shutter || !shutter->is_array() || shutter->size() != 2 || !(*shutter)[0].is_number() ||
      !(*shutter)[1].is_number())
    return nullptr;
  const double t0 = frame + (*shutter)[0].get<double>(), t1 = frame + (*shutter)[1].get<double>();
  std::vector<double> times{t0};
  if (t1 > t0) {
    std::vector<double> keys;
    bool smooth = false;
    collect_key_times(doc, keys, smooth);
    times.push_back(t1);
    for (double t : keys)
      if (t > t0 && t < t1) times.push_back(t);
    if (smooth)
      for (int k = 1; k <= 8; ++k) times.push_back(t0 + (t1 - t0) * k / 9.0);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
  }
  nlohmann::json state = nlohmann::json::array();
  for (double t : times) state.push_back(evaluate_keyframes(doc, t, file));
  return state;
}

std::string hash_with_shutter(const std::string& hash, const nlohmann::json& state) {
  if (state.is_null()) return hash;
  return SceneHash(nlohmann::json{hash, state}).hex();
}

}  // namespace vesper

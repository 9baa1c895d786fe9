#include "common/keyframes.h"

#include <cmath>
#include <string_view>
#include <vector>

#include "common/json_reader.h"

namespace vesper {
namespace {

constexpr std::string_view kInterpolations[] = {"linear", "smooth"};

struct Key {
  double frame = 0;
  std::vector<double> value;  // one component for a number
};

struct Track {
  std::vector<Key> keys;
  bool smooth = false;
  bool scalar = true;  // values are numbers, not arrays
};

Track read_track(const JsonReader& object) {
  JsonReader node = object;
  node.expect_object();
  node.allow_keys({"keys", "interp"});
  Track track;
  track.smooth = node.enumeration("interp", 0, kInterpolations) == 1;
  JsonReader keys = node.array("keys");
  if (keys.size() == 0) keys.fail("expected at least one key [frame, value], got an empty array");
  for (size_t i = 0; i < keys.size(); ++i) {
    JsonReader key = keys.element(i);
    key.expect_array();
    if (key.size() != 2)
      key.fail("expected a key [frame, value], got " + describe_json(key.json()));
    Key k;
    k.frame = key.element(0).as_number();
    const JsonReader value = key.element(1);
    const bool scalar = value.json().is_number();
    if (scalar) {
      k.value = {value.as_number()};
    } else if (value.json().is_array() && value.size() > 0) {
      k.value = value.as_number_array();
    } else {
      value.fail("expected a number or an array of numbers, got " + describe_json(value.json()));
    }
    if (i == 0) {
      track.scalar = scalar;
    } else {
      const Key& prev = track.keys.back();
      if (!(k.frame > prev.frame))
        key.element(0).fail("expected frames in increasing order, got " +
                            describe_json(key.element(0).json()) + " after " +
                            describe_json(keys.element(i - 1).element(0).json()));
      if (scalar != track.scalar || k.value.size() != prev.value.size())
        value.fail("expected a value of the first key's shape (" +
                   describe_json(keys.element(0).element(1).json()) + "), got " +
                   describe_json(value.json()));
    }
    track.keys.push_back(std::move(k));
  }
  node.finish();
  return track;
}

// Zero at the ends (so the held values join with C1 continuity), Catmull-Rom
// for unevenly spaced keys inside.
double tangent(const std::vector<Key>& keys, size_t k, size_t c) {
  if (k == 0 || k + 1 == keys.size()) return 0;
  return (keys[k + 1].value[c] - keys[k - 1].value[c]) / (keys[k + 1].frame - keys[k - 1].frame);
}

std::vector<double> value_at(const Track& track, double time) {
  const std::vector<Key>& keys = track.keys;
  if (!(time > keys.front().frame)) return keys.front().value;
  if (!(time < keys.back().frame)) return keys.back().value;
  size_t k = 0;
  while (keys[k + 1].frame <= time) ++k;
  const Key& a = keys[k];
  const Key& b = keys[k + 1];
  const double h = b.frame - a.frame;
  const double s = (time - a.frame) / h;
  std::vector<double> out(a.value.size());
  for (size_t c = 0; c < out.size(); ++c) {
    if (!track.smooth) {
      out[c] = a.value[c] + s * (b.value[c] - a.value[c]);
      continue;
    }
    const double s2 = s * s, s3 = s2 * s;
    out[c] = (2 * s3 - 3 * s2 + 1) * a.value[c] + (s3 - 2 * s2 + s) * h * tangent(keys, k, c) +
             (-2 * s3 + 3 * s2) * b.value[c] + (s3 - s2) * h * tangent(keys, k + 1, c);
  }
  return out;
}

// A whole number as an integer, as a scene writes it: a key that holds a
// file's own value (30, not 30.0) gives the same document, and so the same
// scene hash, as the value written without keys.
nlohmann::json as_json_number(double v) {
  if (v == std::trunc(v) && std::abs(v) < 0x1p53) return int64_t(v);
  return v;
}

void evaluate_in_place(nlohmann::json& node, double time, const std::string& file,
                       const std::string& path) {
  if (is_keyframed(node)) {
    node = keyframed_value(node, time, file, path);
  } else if (node.is_object()) {
    for (auto& [key, value] : node.items())
      evaluate_in_place(value, time, file, json_pointer_append(path, key));
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      evaluate_in_place(node[i], time, file, json_pointer_append(path, i));
  }
}

}  // namespace

bool is_keyframed(const nlohmann::json& node) { return node.is_object() && node.contains("keys"); }

bool has_keyframes(const nlohmann::json& doc) {
  if (is_keyframed(doc)) return true;
  if (doc.is_structured())
    for (const auto& value : doc)
      if (has_keyframes(value)) return true;
  return false;
}

nlohmann::json keyframed_value(const nlohmann::json& node, double time, const std::string& file,
                               const std::string& path) {
  const Track track = read_track(JsonReader(node, file, path));
  const std::vector<double> v = value_at(track, time);
  for (double c : v)
    if (!std::isfinite(c))
      JsonReader(node, file, path)
          .fail(
              "expected keys whose interpolation stays within the double range; it overflows "
              "at frame " +
              std::to_string(time));
  if (track.scalar) return as_json_number(v[0]);
  nlohmann::json out = nlohmann::json::array();
  for (double c : v) out.push_back(as_json_number(c));
  return out;
}

nlohmann::json evaluate_keyframes(const nlohmann::json& doc, double time, const std::string& file) {
  nlohmann::json out = doc;
  evaluate_in_place(out, time, file, "");
  return out;
}

}  // namespace vesper

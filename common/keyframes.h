#pragma once
// Keyframed values (docs/scene-format.md, "Animation"). Wherever a scene
// expects a number or a vector of numbers, the object
//   {"keys": [[frame, value], ...], "interp": "linear" | "smooth"}
// gives it per frame. Frames are numbers (a fractional time lies between
// frames, as the shutter of a motion-blurred frame does), strictly
// increasing; every value has the same shape (a number, or an array of
// numbers of one length). Before the first key the first value holds, after
// the last the last value holds. "interp" defaults to "linear".
//
// "smooth" is a cubic Hermite spline per component with Catmull-Rom tangents
// for unevenly spaced keys, m_k = (v[k+1] - v[k-1]) / (t[k+1] - t[k-1]), and a
// zero tangent at the first and the last key: C1 everywhere, across the held
// ends too, and it passes through every key.
//
// Evaluation is a transformation of the JSON document, so the scene loader,
// the farm's per-frame result reuse and the scene hash all see one evaluated
// document per time (DESIGN.md, "Scenes change over time").
#include <string>

#include <nlohmann/json.hpp>

namespace vesper {

// True when `node` is a keyframe object: a JSON object with a "keys" member.
bool is_keyframed(const nlohmann::json& node);

// True when any value of `doc`, at any depth, is a keyframe object.
bool has_keyframes(const nlohmann::json& doc);

// `doc` with every keyframe object replaced by its value at `time` (frames).
// Throws JsonError naming `file`, the keyframe object's JSON path and what was
// expected when one is malformed (no keys, frames not increasing, values of
// different shapes, an unknown "interp", another member beside keys/interp).
nlohmann::json evaluate_keyframes(const nlohmann::json& doc, double time, const std::string& file);

// One keyframe object's value at `time`; `path` is its JSON pointer (for
// errors). Same checks as evaluate_keyframes.
nlohmann::json keyframed_value(const nlohmann::json& node, double time, const std::string& file,
                               const std::string& path);

}  // namespace vesper

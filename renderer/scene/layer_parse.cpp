// Parses "layers": named selections of the beauty's light paths and variant
// renders. Needs the scene's lights (for the light groups) and media (for
// variant overrides), so the loader calls it after both.
#include <algorithm>
#include <set>

#include "renderer/scene/scene_parse.h"

namespace vesper {
namespace {

constexpr std::string_view kPathSelections[] = {"all", "surface", "volume"};
constexpr std::string_view kOverrideKeys[] = {"density_scale", "sigma_a", "sigma_s", "g",
                                              "enabled"};

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The light groups a layer may name: lights[].group in name order, then
// "default" when some light has no group, then "emission" (always: emission
// from media, which a scene without emitting media simply has none of).
struct LightGroups {
  std::vector<std::string> names;
  bool has_default = false;

  explicit LightGroups(const std::vector<LightDesc>& lights) {
    std::set<std::string> groups;
    for (const LightDesc& l : lights) {
      if (l.group.empty()) {
        has_default = true;
      } else {
        groups.insert(l.group);
      }
    }
    names.assign(groups.begin(), groups.end());
    if (has_default) names.push_back(std::string(kDefaultLightGroup));
    names.push_back(std::string(kEmissionLightGroup));
  }
  bool contains(const std::string& g) const {
    return std::find(names.begin(), names.end(), g) != names.end();
  }
};

// An array of distinct known group names; `allow_empty` for a variant's lights.
std::vector<std::string> parse_group_list(const JsonReader& node, const LightGroups& groups,
                                          bool allow_empty) {
  const std::string expected =
      std::string(allow_empty ? "an array" : "a non-empty array") + " of light group names";
  if (!node.json().is_array() || (!allow_empty && node.size() == 0)) {
    node.fail("expected " + expected + ", got " + describe_json(node.json()) +
              (node.json().is_array() ? " (leave out 'lights' to keep every group)" : ""));
  }
  std::vector<std::string> out;
  for (size_t i = 0; i < node.size(); ++i) {
    const JsonReader e = node.element(i);
    const std::string g = e.as_string();
    if (const auto it = std::find(out.begin(), out.end(), g); it != out.end()) {
      e.fail("duplicate light group \"" + g + "\" (already at " +
             json_pointer_append(node.path(), size_t(it - out.begin())) + ")");
    }
    if (!groups.contains(g)) {
      std::string message =
          "unknown light group \"" + g + "\" (known groups: " + join(groups.names) + ")";
      if (g == kDefaultLightGroup) {
        message +=
            "; \"default\" is the group of the lights without a 'group', and every light has one";
      }
      e.fail(message);
    }
    out.push_back(g);
  }
  return out;
}

MediumOverride parse_override(JsonReader node) {
  node.expect_object();
  node.allow_keys({"density_scale", "sigma_a", "sigma_s", "g", "enabled"});
  if (node.json().empty()) {
    std::string keys;
    for (std::string_view k : kOverrideKeys) keys += (keys.empty() ? "" : ", ") + std::string(k);
    node.fail("expected at least one of " + keys +
              ", got an empty object (an override without keys changes nothing)");
  }
  MediumOverride o;
  // On a homogeneous medium density_scale multiplies sigma_a and sigma_s
  // (after their overrides), as if it were a grid of density 1.
  if (const auto scale = node.optional_child("density_scale"))
    o.density_scale = scale->as_number(Range::non_negative());
  if (const auto c = node.optional_child("sigma_a")) o.sigma_a = as_rgb(*c, Range::non_negative());
  if (const auto c = node.optional_child("sigma_s")) o.sigma_s = as_rgb(*c, Range::non_negative());
  if (const auto c = node.optional_child("g")) o.g = c->as_number(Range::open(-1, 1));
  if (node.has("enabled")) o.enabled = node.boolean("enabled", true);
  return o;
}

VariantDesc parse_variant(JsonReader node, const LightGroups& groups,
                          const std::vector<MediumDesc>& media) {
  node.expect_object();
  node.allow_keys({"media", "lights"});
  if (node.json().empty()) {
    node.fail(
        "expected 'media' and/or 'lights' in a variant, got an empty object "
        "(a layer without a variant needs no 'variant' key)");
  }
  VariantDesc v;
  if (const auto overrides = node.optional_child("media")) {
    overrides->expect_object();
    for (const auto& [name, value] : overrides->json().items()) {
      const JsonReader o(value, node.file(), overrides->key_path(name));
      const auto medium = std::find_if(media.begin(), media.end(),
                                       [&](const MediumDesc& m) { return m.name == name; });
      if (medium == media.end()) {
        std::vector<std::string> names;
        for (const MediumDesc& m : media) names.push_back(m.name);
        o.fail("unknown medium \"" + name + "\" (" +
               (names.empty() ? std::string("the scene has no media")
                              : "known media: " + join(names)) +
               ")");
      }
      v.media.emplace(name, parse_override(o));
    }
  }
  if (const auto lights = node.optional_child("lights")) {
    v.lights = parse_group_list(*lights, groups, /*allow_empty=*/true);
  }
  return v;
}

bool valid_layer_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

LayerDesc parse_layer(JsonReader node, const std::string& name, const LightGroups& groups,
                      const std::vector<MediumDesc>& media) {
  if (name.empty()) node.fail("expected a non-empty layer name");
  if (!std::all_of(name.begin(), name.end(), valid_layer_name_char)) {
    node.fail(
        "expected a layer name of letters, digits, '_' and '-' (it prefixes the EXR "
        "channels, as in '<layer>.R'), got \"" +
        name + "\"");
  }
  if (name == "beauty" ||
      std::find(std::begin(kAovNames), std::end(kAovNames), name) != std::end(kAovNames)) {
    std::string reserved = "beauty";
    for (std::string_view a : kAovNames) reserved += ", " + std::string(a);
    node.fail("expected a layer name other than the names of the beauty and the standard AOVs (" +
              reserved + "), got \"" + name + "\"");
  }
  if (name.rfind("CryptoObject", 0) == 0 || name.rfind("CryptoMaterial", 0) == 0)
    node.fail(
        "expected a layer name that does not start with CryptoObject or CryptoMaterial "
        "(the channels of the cryptomatte AOV), got \"" +
        name + "\"");
  node.expect_object();
  node.allow_keys({"paths", "lights", "variant"});
  LayerDesc layer;
  layer.name = name;
  layer.paths = static_cast<PathSelection>(node.enumeration("paths", 0, kPathSelections));
  if (const auto variant = node.optional_child("variant")) {
    layer.variant = parse_variant(*variant, groups, media);
  }
  if (const auto lights = node.optional_child("lights")) {
    layer.lights = parse_group_list(*lights, groups, /*allow_empty=*/false);
    // A group the variant switches off contributes nothing to the layer.
    if (layer.variant && layer.variant->lights) {
      const std::vector<std::string>& active = *layer.variant->lights;
      for (size_t i = 0; i < layer.lights->size(); ++i) {
        const std::string& g = (*layer.lights)[i];
        if (std::find(active.begin(), active.end(), g) == active.end()) {
          lights->element(i).fail("expected a light group that the variant keeps (" +
                                  (active.empty() ? std::string("none") : join(active)) +
                                  "), got \"" + g + "\", which would leave the layer black");
        }
      }
    }
  }
  return layer;
}

}  // namespace

std::vector<LayerDesc> parse_layers(JsonReader node, const std::vector<LightDesc>& lights,
                                    const std::vector<MediumDesc>& media) {
  node.expect_object();
  const LightGroups groups(lights);
  std::vector<LayerDesc> layers;
  // nlohmann's objects iterate in key order, so layers come sorted by name.
  for (const auto& [name, value] : node.json().items()) {
    layers.push_back(
        parse_layer(JsonReader(value, node.file(), node.key_path(name)), name, groups, media));
  }
  return layers;
}

}  // namespace vesper

// Every malformed scene under data/bad_scenes/ must be rejected with a
// SceneError naming the file, the JSON path and what was expected.
#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "renderer/scene/scene_loader.h"

namespace vesper {
namespace {

const std::filesystem::path kBadDir = std::filesystem::path(VESPER_TEST_DATA_DIR) / "bad_scenes";

struct BadScene {
  const char* file;
  const char* path;     // substring of the JSON path (or "line L, column C" for syntax errors)
  const char* message;  // substring of the message
};

void PrintTo(const BadScene& s, std::ostream* os) { *os << s.file; }

// clang-format off
const BadScene kBadScenes[] = {
    {"bad_type_radius.json", "/shapes/0/radius", "expected a positive number, got string \"1\""},
    {"missing_camera.json", "/", "missing required key 'camera'"},
    {"shape_duplicate_name.json", "/shapes/1/name", "expected a unique shape name, got \"sphere0\", the name of /shapes/0 already"},
    {"unknown_key_shape.json", "/shapes/0/radus", "unknown key 'radus' (expected one of: type, center, radius, material, name); did you mean 'radius'?"},
    {"typo_in_material_key.json", "/materials/white/albdo", "did you mean 'albedo'?"},
    {"nan_literal.json", "line 27, column", "invalid JSON"},
    {"inf_number.json", "line 27, column 17", "number overflow parsing '1e999'"},
    {"negative_radius.json", "/shapes/0/radius", "expected a positive number, got -1"},
    {"unknown_material.json", "/shapes/0/material", "unknown material \"blu\" (known materials: white)"},
    {"missing_mesh_file.json", "/shapes/0/file", "mesh file not found"},
    {"mesh_file_wrong_extension.json", "/shapes/0/file", "expected a .ply or .obj mesh file"},
    {"mesh_file_unparsable.json", "/shapes/0/file", "broken.ply': invalid PLY header: no 'end_header' line"},
    {"mesh_file_without_triangles.json", "/shapes/0/file", "points_only.ply' contains no triangles"},
    {"mesh_file_and_positions.json", "/shapes/0", "either 'file' or 'positions' + 'indices', not both"},
    {"wrong_format_version.json", "/format", "expected \"vesper-scene/1\", got string \"vesper-scene/2\""},
    {"fov_out_of_range.json", "/camera/fov", "expected a number in (0, 180), got 180"},
    {"indices_out_of_range.json", "/shapes/0/indices/5", "expected an integer in [0, 3], got 4"},
    {"positions_not_multiple_of_3.json", "/shapes/0/positions", "multiple of 3"},
    {"two_environments.json", "/lights/1", "at most one environment light"},
    {"spot_falloff_greater_than_cone.json", "/lights/0/falloff_start", "expected falloff_start <= cone_angle (30), got 35"},
    {"radiance_negative.json", "/lights/0/radiance/1", "expected a non-negative number, got -1"},
    {"width_not_integer.json", "/film/width", "expected an integer in [1, 65536], got 64.5"},
    {"trailing_comma.json", "line 9, column", "invalid JSON"},
    {"env_file_and_radiance.json", "/lights/0", "either 'radiance' or 'file', not both"},
    {"missing_env_file.json", "/lights/0/file", "environment image not found"},
    {"transform_both_forms.json", "/shapes/0/transform", "not both forms"},
    {"matrix_last_row_not_affine.json", "/shapes/0/transform/matrix", "last row is [0, 0, 0, 1]"},
    {"matrix_singular.json", "/shapes/0/transform/matrix", "non-singular"},
    {"rotate_axis_zero.json", "/shapes/0/transform/rotate/axis", "non-zero rotation axis"},
    {"unknown_light_type.json", "/lights/0/type", "expected one of \"quad\", \"point\", \"spot\", \"sun\", \"environment\", got string \"area\""},
    {"spp_zero.json", "/render/spp", "expected an integer in [1, 2147483647], got 0"},
    {"noise_target_zero.json", "/render/noise_target", "expected a positive number, got 0"},
    {"noise_target_negative.json", "/render/noise_target", "expected a positive number, got -0.05"},
    {"min_spp_over_max_spp.json", "/render/min_spp", "min_spp 64 is greater than max_spp 16"},
    {"time_limit_zero.json", "/render/time_limit", "expected a positive number, got 0"},
    {"clamp_negative.json", "/render/clamp", "expected a positive number, got -2"},
    {"photon_radius_zero.json", "/render/photon_radius", "expected a positive number, got 0"},
    {"photon_merging_not_bool.json", "/render/photon_merging", "expected true or false, got string \"yes\""},
    {"unknown_aov.json", "/render/aovs/1", "expected one of \"albedo\", \"normal\", \"depth\", \"emission\", \"diffuse_direct\", \"diffuse_indirect\", \"specular_direct\", \"specular_indirect\", \"volume_direct\", \"volume_indirect\", \"variance\", \"spp\", \"cryptomatte\", got string \"normals\""},
    {"unknown_aov_transport.json", "/render/aovs/1", "expected one of \"albedo\", \"normal\", \"depth\", \"emission\", \"diffuse_direct\", \"diffuse_indirect\", \"specular_direct\", \"specular_indirect\", \"volume_direct\", \"volume_indirect\", \"variance\", \"spp\", \"cryptomatte\", got string \"diffuse\""},
    {"duplicate_aov.json", "/render/aovs/2", "duplicate AOV \"depth\" (already at /render/aovs/0)"},
    {"duplicate_aov_transport.json", "/render/aovs/3", "duplicate AOV \"volume_direct\" (already at /render/aovs/1)"},
    {"duplicate_key.json", "/shapes/0/radius", "duplicate key 'radius'"},
    {"up_parallel_to_view.json", "/camera/up", "not parallel to the view direction"},
    {"camera_from_equals_to.json", "/camera/to", "differ from 'from'"},
    {"albedo_above_one.json", "/materials/white/albedo/0", "expected a number in [0, 1], got 1.2"},
    {"rgb_two_components.json", "/materials/white/albedo", "expected an RGB array of 3 numbers"},
    {"sun_direction_zero.json", "/lights/0/direction", "expected a non-zero direction"},
    {"empty_group.json", "/lights/0/group", "expected a non-empty string"},
    {"shapes_not_array.json", "/shapes", "expected an array, got an object"},
    {"seed_negative.json", "/render/seed", "got -1"},
    {"unknown_top_level_key.json", "/lihgts", "did you mean 'lights'?"},
    {"conductor_eta_zero.json", "/materials/gold/eta/0", "expected a positive number, got 0"},
    {"top_level_array.json", "/", "expected an object, got an array"},
    {"empty_file.json", "line 1, column 1", "invalid JSON"},
    {"medium_unknown_type.json", "/media/fog/type", "expected one of \"homogeneous\", \"vdb\", got string \"heterogeneous\""},
    {"medium_g_one.json", "/media/fog/g", "expected a number in (-1, 1), got 1"},
    {"medium_sigma_s_negative.json", "/media/fog/sigma_s/1", "expected a non-negative number, got -0.5"},
    {"medium_sigma_s_missing.json", "/media/fog", "missing required key 'sigma_s'"},
    {"medium_bounds_min_not_below_max.json", "/media/fog/bounds", "expected min < max on every axis, got min.y = 2 and max.y = 2"},
    {"medium_vdb_missing_file.json", "/media/smoke/file", "VDB file not found: '" VESPER_TEST_DATA_DIR "/bad_scenes/volumes/no_such_smoke.vdb'"},
    {"medium_emission_scale_without_grid.json", "/media/smoke/emission_scale", "emission_scale > 0 needs 'emission_grid'"},
    {"medium_unknown_key.json", "/media/fog/sigma_t", "unknown key 'sigma_t' (expected one of: type, sigma_a, sigma_s, g, bounds)"},
    {"medium_density_scale_negative.json", "/media/smoke/density_scale", "expected a non-negative number, got -2"},
    {"medium_empty_name.json", "/media/: ", "expected a non-empty medium name"},
    {"media_not_object.json", "/media", "expected an object, got an array of 1 elements"},
    {"light_group_named_emission.json", "/lights/1/group", "expected a group name other than \"emission\" (reserved for emission from media), got \"emission\""},
    {"light_group_named_default.json", "/lights/0/group", "expected a group name other than \"default\""},
    {"layers_not_object.json", "/layers", "expected an object, got an array of 1 elements"},
    {"layer_unknown_light_group.json", "/layers/lightrays/lights/0", "unknown light group \"windows\" (known groups: candles, window, emission)"},
    {"layer_default_group_without_ungrouped_lights.json", "/layers/rest/lights/0", "unknown light group \"default\" (known groups: candles, window, emission); \"default\" is the group of the lights without a 'group', and every light has one"},
    {"layer_duplicate_light_group.json", "/layers/rays/lights/2", "duplicate light group \"window\" (already at /layers/rays/lights/0)"},
    {"layer_lights_empty.json", "/layers/none/lights", "expected a non-empty array of light group names, got an array of 0 elements"},
    {"layer_unknown_paths.json", "/layers/fog/paths", "expected one of \"all\", \"surface\", \"volume\", got string \"volumes\""},
    {"layer_name_with_dot.json", "/layers/fog.dense", "expected a layer name of letters, digits, '_' and '-' (it prefixes the EXR channels, as in '<layer>.R'), got \"fog.dense\""},
    {"layer_named_like_cryptomatte.json", "/layers/CryptoObject00", "expected a layer name that does not start with CryptoObject or CryptoMaterial (the channels of the cryptomatte AOV), got \"CryptoObject00\""},
    {"layer_named_like_aov.json", "/layers/albedo", "expected a layer name other than the names of the beauty and the standard AOVs (beauty, albedo, normal, depth, emission, diffuse_direct, diffuse_indirect, specular_direct, specular_indirect, volume_direct, volume_indirect, variance, spp, cryptomatte), got \"albedo\""},
    {"layer_unknown_key.json", "/layers/fog/path", "unknown key 'path' (expected one of: paths, lights, variant); did you mean 'paths'?"},
    {"layer_empty_variant.json", "/layers/fog/variant", "expected 'media' and/or 'lights' in a variant, got an empty object"},
    {"layer_variant_unknown_medium.json", "/layers/rays_dense/variant/media/smoke", "unknown medium \"smoke\" (known media: fog)"},
    {"layer_empty_medium_override.json", "/layers/thin/variant/media/fog", "expected at least one of density_scale, sigma_a, sigma_s, g, enabled, got an empty object"},
    {"layer_group_off_in_variant.json", "/layers/glow/lights/0", "expected a light group that the variant keeps (window), got \"candles\""},
};
// clang-format on

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, IsRejectedWithPathAndReason) {
  const BadScene& s = GetParam();
  const std::filesystem::path file = kBadDir / s.file;
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  try {
    load_scene(file);
    FAIL() << s.file << " was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(s.path), std::string::npos) << "path '" << s.path << "' not in: " << what;
    EXPECT_NE(what.find(s.message), std::string::npos)
        << "message '" << s.message << "' not in: " << what;
    EXPECT_EQ(e.file(), file.string());
  } catch (const std::exception& e) {
    FAIL() << s.file << " threw a non-SceneError: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadSceneTest, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.rfind('.'));
                           std::replace_if(
                               name.begin(), name.end(), [](char c) { return !std::isalnum(c); },
                               '_');
                           return name;
                         });

// A file added to bad_scenes/ without an expectation here would test nothing.
TEST(BadScenes, EveryFileHasAnExpectationAndViceVersa) {
  std::set<std::string> on_disk, in_table;
  for (const auto& entry : std::filesystem::directory_iterator(kBadDir)) {
    on_disk.insert(entry.path().filename().string());
  }
  for (const BadScene& s : kBadScenes) {
    EXPECT_TRUE(in_table.insert(s.file).second) << "listed twice: " << s.file;
  }
  for (const std::string& f : on_disk) EXPECT_TRUE(in_table.count(f)) << "no expectation: " << f;
  for (const std::string& f : in_table) EXPECT_TRUE(on_disk.count(f)) << "missing file: " << f;
  EXPECT_GE(on_disk.size(), 22u);
}

}  // namespace
}  // namespace vesper

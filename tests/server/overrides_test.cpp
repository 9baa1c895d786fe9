// Render overrides through the server (docs/farm.md, "Render overrides"):
// the submit keys are validated naming their JSON path, and each lease
// carries them; a job without them leases as before.
#include <gtest/gtest.h>

#include "tests/server/server_fixture.h"

using nlohmann::json;

namespace vesper {
namespace {

class OverridesTest : public ServerTest {
 protected:
  json job_body(const json& overrides) {
    json body{{"scene", put_blob("{\"format\": \"vesper-scene/1\"}")}, {"frames", "1"}};
    body.update(overrides);
    return body;
  }
  // The 400 answer's `path` and message for a submit with these keys.
  std::pair<std::string, std::string> refusal(const json& overrides) {
    auto r = post("/jobs", job_body(overrides), sub());
    if (!r) return {"no answer", ""};
    if (r->status != 400) return {"status " + std::to_string(r->status), r->body};
    const json e = json::parse(r->body);
    return {e.value("path", ""), e.value("error", "")};
  }
};

TEST_F(OverridesTest, BadKeysAreRefusedNamingTheirPath) {
  start();
  EXPECT_EQ(refusal({{"aovs", json::array()}}).first, "/aovs");
  EXPECT_EQ(refusal({{"aovs", "variance"}}).first, "/aovs");
  const auto unknown = refusal({{"aovs", {"variance", "albdo"}}});
  EXPECT_EQ(unknown.first, "/aovs/1");
  EXPECT_NE(unknown.second.find("\"albedo\""), std::string::npos) << unknown.second;
  EXPECT_EQ(refusal({{"aovs", {"variance", "variance"}}}).first, "/aovs/1");
  EXPECT_EQ(refusal({{"layer_variance", 1}}).first, "/layer_variance");
  EXPECT_EQ(refusal({{"seed", -1}}).first, "/seed");
  EXPECT_EQ(refusal({{"seed", 1.5}}).first, "/seed");
  EXPECT_EQ(refusal({{"scale", 0}}).first, "/scale");
  EXPECT_EQ(refusal({{"scale", 4.5}}).first, "/scale");
  EXPECT_EQ(refusal({{"half", "yes"}}).first, "/half");
  EXPECT_EQ(refusal({{"sacle", 0.5}}).first, "/sacle");
  EXPECT_TRUE(get_ok("/jobs").at("jobs").empty());
}

// Partials carry Cryptomatte's counts: a job asking for it may split frames.
TEST_F(OverridesTest, CryptomatteJobsMaySplitFrames) {
  start();
  const auto id =
      post_ok("/jobs", job_body({{"aovs", {"cryptomatte"}}, {"spp", 64}, {"samples_per_task", 16}}),
              sub(), 201)
          .at("id")
          .get<int64_t>();
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(id)).at("tasks").size(), 4u);  // [0,16) ... [48,64)
}

TEST_F(OverridesTest, EachLeaseCarriesTheJobsOverrides) {
  start();
  post_ok("/jobs",
          job_body({{"aovs", {"variance", "albedo"}},
                    {"layer_variance", true},
                    {"seed", 9007199254740993ull},
                    {"scale", 0.25},
                    {"half", true}}),
          sub(), 201);
  post_ok("/jobs", job_body(json::object()), sub(), 201);
  const std::string w = register_worker("w");
  const json l = lease(w);
  EXPECT_EQ(l.at("aovs"), json({"variance", "albedo"}));
  EXPECT_EQ(l.at("layer_variance"), true);
  EXPECT_EQ(l.at("seed").get<uint64_t>(), 9007199254740993ull);
  EXPECT_EQ(l.at("scale"), 0.25);
  EXPECT_EQ(l.at("half"), true);
  const json plain = lease(w);
  for (const char* key : {"aovs", "layer_variance", "seed", "scale", "half"})
    EXPECT_FALSE(plain.contains(key)) << plain.dump();
}

}  // namespace
}  // namespace vesper

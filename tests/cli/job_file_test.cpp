// The job file reader (cli/job_file.h) and how `vesper submit` tells a job
// file from a scene.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/job_file.h"
#include "common/json_error.h"
#include "tests/common/cli_runner.h"

namespace vesper {
namespace {

TEST(JobFile, ReadsTheKeysOverTheDefaults) {
  cli::JobRequest defaults;
  defaults.frames = "1";
  defaults.priority = 10;
  const cli::JobRequest r = cli::parse_job_file_text(
      R"({"format": "vesper-job/1", "scene": "shot/scene.json", "frames": 7, "spp": 32})",
      "jobs/job.json", defaults);
  EXPECT_EQ(r.scene, std::filesystem::path("jobs/shot/scene.json"));
  EXPECT_EQ(r.name, "shot");
  EXPECT_EQ(r.frames, "7");
  EXPECT_EQ(r.spp, 32);
  EXPECT_EQ(r.priority, 10);
}

// Found by the job fuzz target: a "format" that is not a string made the
// check nlohmann's type_error ("type must be string, but is number").
TEST(JobFile, FormatOfAnotherTypeIsNotAJobFileAndNeverThrows) {
  for (const char* text : {R"({"format": 5})", R"({"format": ["vesper-job/1"]})",
                           R"({"format": null})", R"({"format": {"a": 1}})", "[1]", "",
                           "{\"format\": \"vesper-job/1\"", R"({"format": 1e400})"}) {
    bool is_job = true;
    EXPECT_NO_THROW(is_job = cli::is_job_file_text(text)) << text;
    EXPECT_FALSE(is_job) << text;
  }
  EXPECT_TRUE(cli::is_job_file_text(R"({"format": "vesper-job/1"})"));
  try {
    cli::parse_job_file_text(R"({"format": 5, "scene": "s.json"})", "job.json", {});
    ADD_FAILURE() << "accepted";
  } catch (const JsonError& e) {
    EXPECT_EQ(e.json_path(), "/format") << e.what();
  }
}

// "half" (render override): a boolean; anything else is an error naming the
// file and the key.
TEST(JobFile, HalfIsABooleanAndAnotherTypeNamesTheKey) {
  const char* head = R"({"format": "vesper-job/1", "scene": "s.json", )";
  EXPECT_TRUE(cli::parse_job_file_text(std::string(head) + R"("half": true})", "job.json", {})
                  .overrides.half);
  EXPECT_FALSE(
      cli::parse_job_file_text(std::string(head) + R"("spp": 4})", "job.json", {}).overrides.half);
  for (const char* bad : {R"("yes")", "1", "null"}) {
    try {
      cli::parse_job_file_text(std::string(head) + R"("half": )" + bad + "}", "job.json", {});
      ADD_FAILURE() << "accepted " << bad;
    } catch (const JsonError& e) {
      EXPECT_EQ(e.json_path(), "/half") << e.what();
      EXPECT_NE(std::string(e.what()).find("job.json"), std::string::npos) << e.what();
    }
  }
}

class JobFileCli : public test::CliTest {
 protected:
  JobFileCli() : CliTest("submit") {}
};

// Before the fix: exit 2 with "[json.exception.type_error.302] type must be
// string, but is number" and no file or JSON path.
TEST_F(JobFileCli, FormatOfAnotherTypeIsAClearError) {
  const auto file = dir_ / "job.json";
  std::ofstream(file) << R"({"format": 5, "scene": "scene.json"})";
  const test::RunResult r = run(file.string() + " --server http://127.0.0.1:9 --token t");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.find("type_error"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("job.json: /format: expected"), std::string::npos) << r.err;
}

TEST_F(JobFileCli, ABadHalfKeyIsAClearError) {
  const auto file = dir_ / "job.json";
  std::ofstream(file) << R"({"format": "vesper-job/1", "scene": "scene.json", "half": "yes"})";
  const test::RunResult r = run(file.string() + " --server http://127.0.0.1:9 --token t");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("job.json: /half: expected"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace vesper

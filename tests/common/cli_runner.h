#pragma once
// Runs the real `vesper` binary in a fresh temporary directory per test and
// captures its exit code, stdout and stderr (tests of the CLI as users run it).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/temp_dir.h"

namespace vesper::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class CliTest : public ::testing::Test {
 protected:
  // `subcommand` is put before the arguments of every run() ("render", "vdb", ...).
  explicit CliTest(std::string subcommand) : subcommand_(std::move(subcommand)) {}

  RunResult run(const std::string& args) {
    const auto out = dir_ / ".stdout.txt", err = dir_ / ".stderr.txt";
    const std::string cmd = std::string(VESPER_BINARY) + " " + subcommand_ + " " + args + " >" +
                            out.string() + " 2>" + err.string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }

  TempDir temp_{"cli"};
  std::filesystem::path dir_ = temp_.path();
  std::string subcommand_;
};

}  // namespace vesper::test

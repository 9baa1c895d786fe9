#pragma once
// A scratch directory for one test: created empty under the system temp
// directory with a unique name (mkdtemp: parallel ctest runs and repeated
// tests never share one), named after the running test so a kept one is easy
// to find, and removed with everything in it on destruction — unless the
// environment variable VESPER_KEEP_TEST_DIRS is set (to anything but "0"),
// which keeps it for a post-mortem and prints its path.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace vesper::test {

class TempDir {
 public:
  // `prefix` says which suite it belongs to: <tmp>/vesper-<prefix>-<Suite.Test>-XXXXXX.
  explicit TempDir(const std::string& prefix = "test") {
    std::string name = "vesper-" + prefix + "-";
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
      name += std::string(info->test_suite_name()) + "." + info->name() + "-";
    for (char& c : name)  // parameterised tests are named "Suite/Test/0"
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    std::string pattern = (std::filesystem::temp_directory_path() / name.substr(0, 200)).string();
    pattern += "XXXXXX";
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error("mkdtemp " + pattern + ": " + std::strerror(errno));
    path_ = pattern;
  }
  ~TempDir() {
    const char* keep = std::getenv("VESPER_KEEP_TEST_DIRS");
    if (keep && std::string(keep) != "0") {
      std::cerr << "kept test directory " << path_.string() << "\n";
      return;
    }
    std::error_code ec;  // a destructor must not throw; a leftover is harmless
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace vesper::test

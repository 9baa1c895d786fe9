// fuzz_target.h: findings, the accepted count and the sandbox folder.
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "tests/fuzz/fuzz_target.h"

namespace vesper::fuzz {
namespace {

long long g_accepted = 0;

void touch(const std::filesystem::path& p, const std::string& text = {}) {
  std::ofstream(p, std::ios::binary) << text;
}

struct Sandbox {
  std::filesystem::path dir;
  Sandbox() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vesper-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      std::perror("vesper fuzz: mkdtemp");
      std::abort();
    }
    dir = pattern;
    for (const char* f : {"frame.exr", "frame.0001.exr", "frame.0002.exr", "other.0001.exr",
                          "other.0002.exr", "look.cube", "config.ocio"})
      touch(dir / f);
    std::filesystem::create_directory(dir / "out");
    // The scene a job file or suite names (suites check that it exists).
    touch(dir / "scene.json", R"({"format": "vesper-scene/1"})");
  }
  ~Sandbox() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

void finding(const std::string& what) {
  std::fprintf(stderr, "\nvesper fuzz: FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void note_accepted() { ++g_accepted; }
long long accepted_count() { return g_accepted; }

const std::filesystem::path& sandbox() {
  static const Sandbox s;
  return s.dir;
}

}  // namespace vesper::fuzz

// write_file_atomically: the file appears whole, replaces the old one, and a
// failed write leaves the old one untouched and no temporary behind.
#include "common/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "tests/common/temp_dir.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

size_t entries(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  TempDir dir("common");
  write_file_atomically(dir / "a.txt", "first");
  EXPECT_EQ(read_all(dir / "a.txt"), "first");
  write_file_atomically(dir / "a.txt", std::string("sec\0ond", 7));
  EXPECT_EQ(read_all(dir / "a.txt"), std::string("sec\0ond", 7));
  EXPECT_EQ(entries(dir.path()), 1u) << "no temporary left";
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNothingElse) {
  TempDir dir("common");
  write_file_atomically(dir / "a.txt", "old");
  // The temporary's name taken by a non-empty folder: the write cannot start.
  fs::create_directories(dir / (".a.txt.tmp-" + std::to_string(::getpid())) / "x");
  try {
    write_file_atomically(dir / "a.txt", "new");
    FAIL() << "expected FileWriteError";
  } catch (const FileWriteError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "a.txt").string() + ": cannot write"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_all(dir / "a.txt"), "old");
  // A folder where the file should go: written, but cannot be moved into place.
  fs::create_directories(dir / "b.txt" / "x");
  EXPECT_THROW(write_file_atomically(dir / "b.txt", "new"), FileWriteError);
  EXPECT_FALSE(fs::exists(dir / (".b.txt.tmp-" + std::to_string(::getpid()))));
  EXPECT_THROW(write_file_atomically(dir / "missing" / "c.txt", "x"), FileWriteError);
}

}  // namespace
}  // namespace vesper::test

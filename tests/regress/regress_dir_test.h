#pragma once
// The regress suite's fixture for tests that write files: a fresh scratch
// directory (tests/common/temp_dir.h) as `dir_`.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/temp_dir.h"

namespace vesper::test {

class RegressDirTest : public ::testing::Test {
 protected:
  TempDir tmp_{"regress"};
  const std::filesystem::path dir_ = tmp_.path();
};

}  // namespace vesper::test

#include "common/typo_distance.h"

#include <gtest/gtest.h>

namespace vesper {
namespace {

TEST(TypoDistance, CountsInsertDeleteReplace) {
  EXPECT_EQ(typo_distance("", ""), 0u);
  EXPECT_EQ(typo_distance("spp", "spp"), 0u);
  EXPECT_EQ(typo_distance("", "abc"), 3u);
  EXPECT_EQ(typo_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(typo_distance("radus", "radius"), 1u);
}

TEST(TypoDistance, ANeighbourSwapIsOneTypo) {
  EXPECT_EQ(typo_distance("sapmle", "sample"), 1u);  // Levenshtein would say 2
  EXPECT_EQ(typo_distance("ab", "ba"), 1u);
  EXPECT_EQ(typo_distance("abc", "ca"), 3u);  // OSA: no edit of a swapped pair
}

TEST(TypoDistance, IsSymmetric) {
  EXPECT_EQ(typo_distance("--sample-end", "--sapmle-ned"),
            typo_distance("--sapmle-ned", "--sample-end"));
}

}  // namespace
}  // namespace vesper

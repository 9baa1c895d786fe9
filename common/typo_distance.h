#pragma once
// How many single-letter typos separate two names, for "did you mean ...?"
// hints on unknown JSON keys and unknown command-line options alike.
#include <cstddef>
#include <string_view>

namespace vesper {

// Optimal string alignment distance: Levenshtein (insert, delete, replace)
// plus the swap of two neighbouring letters as one edit ("sapmle" is one typo
// from "sample", not two).
size_t typo_distance(std::string_view a, std::string_view b);

}  // namespace vesper

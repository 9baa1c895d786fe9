#pragma once
// "Did you mean ...?" for the command line: the known name nearest to a
// mistyped one. CLI11 2.1 suggests nothing for an unknown option or
// subcommand, so main.cpp asks this with the app's own names.
#include <optional>
#include <string>
#include <vector>

namespace vesper::cli {

// The name nearest to `typed` when it is a likely typo: at most max(1, n/3)
// single-letter edits away (insert, delete, replace, swap two neighbours; n
// = typed's length without leading dashes, and fewer edits than n), else the
// one name that `typed` (2+ letters) begins. nullopt when nothing is close.
std::optional<std::string> nearest_name(const std::string& typed,
                                        const std::vector<std::string>& names);

}  // namespace vesper::cli

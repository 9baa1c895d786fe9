#pragma once
// Subcommand entry points. Each lives in its own .cpp; main.cpp owns CLI11
// and only fills these option structs.
#include <optional>
#include <string>
#include <vector>

namespace vesper::cli {

struct RenderCommandOptions {
  std::string scene;
  std::string output;
  std::optional<int> spp;
  std::optional<int> threads;
  std::optional<unsigned long long> seed;
  std::optional<std::string> aovs;  // comma-separated
  int sample_begin = 0;
  std::optional<int> sample_end;
  bool quiet = false;
};
int run_render(const RenderCommandOptions& options);

}  // namespace vesper::cli

#include "server/merge.h"

#include <unistd.h>

#include <system_error>

#include "process/child_process.h"

namespace fs = std::filesystem;

namespace vesper {

fs::path find_vesper_binary(const fs::path& configured, std::string& problem) {
  problem.clear();
  if (!configured.empty()) {
    if (::access(configured.c_str(), X_OK) == 0) return configured;
    problem = "the configured vesper binary '" + configured.string() + "' is not executable";
    return {};
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    problem = "cannot read /proc/self/exe (" + ec.message() + ") to find the vesper binary";
    return {};
  }
  const fs::path next = self.parent_path() / "vesper";
  if (::access(next.c_str(), X_OK) == 0) return next;
  problem = "no vesper executable next to " + self.string() +
            " (set the server's vesper_binary to merge sample ranges)";
  return {};
}

MergeRun run_vesper_merge(const fs::path& vesper, const std::vector<fs::path>& partials,
                          const fs::path& output, const std::atomic<bool>& stop) {
  std::vector<std::string> argv = {vesper.string(), "merge", "-o", output.string()};
  for (const auto& p : partials) argv.push_back(p.string());
  argv.push_back("-q");
  std::string cmdline;
  for (const auto& a : argv) cmdline += (cmdline.empty() ? "" : " ") + a;
  MergeRun r;
  std::error_code ec;
  try {
    ChildProcess child(argv, 16 * 1024);
    while (!child.wait_for(0.1)) {
      if (stop.load()) {
        child.kill(1);
        fs::remove(output, ec);
        r.aborted = true;
        r.error = "merge aborted: the server is stopping";
        return r;
      }
    }
    if (child.exit_code() == 0 && fs::is_regular_file(output, ec)) {
      r.ok = true;
      return r;
    }
    const std::string status =
        child.exit_code() == 0 ? "exit code 0 but no output file" : child.describe_status();
    r.error = "vesper merge failed: " + status + "\ncommand: " + cmdline +
              "\n--- stderr (tail) ---\n" + child.stderr_tail();
  } catch (const std::exception& e) {
    r.error = std::string("vesper merge could not run: ") + e.what() + "\ncommand: " + cmdline;
  }
  fs::remove(output, ec);
  return r;
}

}  // namespace vesper

// The fuzz driver for compilers without libFuzzer (g++): runs a target's
// LLVMFuzzerTestOneInput on its seed corpus, then on mutations of it
// (mutator.h) with a fixed seed, until a time or run budget is spent. No
// coverage feedback: inputs the parser accepted are kept (up to 512) as
// further starting points, so mutations reach past the first validation
// errors. A finding — a crash or abort (signal), an exception other than the
// target's documented one escaping, or a hang beyond --timeout — prints what
// happened, writes the input to <artifacts>/<target>-finding and exits 1.
//
//   fuzz_scene [--seconds S] [--runs N] [--seed K] [--timeout T] [--artifacts DIR] CORPUS_DIR...
//   fuzz_scene FILE...     run each file once (reproduce a finding)
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "tests/fuzz/driver/mutator.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

namespace fs = std::filesystem;

struct Options {
  double seconds = 10;
  long long runs = 0;  // 0: no limit
  uint64_t seed = 1;
  unsigned timeout = 20;  // seconds one input may take
  fs::path artifacts = ".";
  std::vector<fs::path> corpus_dirs, files;
};

// What the signal handler needs, prepared before each run (it may only call
// async-signal-safe functions).
const std::string* g_input = nullptr;
std::string g_finding_path;

void write_all(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w <= 0) return;
    p += w, n -= size_t(w);
  }
}

void save_input() {
  if (!g_input) return;
  const int fd = ::open(g_finding_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  write_all(fd, g_input->data(), g_input->size());
  ::close(fd);
}

void on_signal(int sig) {
  const char* what = sig == SIGALRM ? "\nvesper fuzz: FINDING: timeout (hang) on an input\n"
                                    : "\nvesper fuzz: FINDING: crash (signal) on an input\n";
  write_all(2, what, std::strlen(what));
  save_input();
  const char* saved = "vesper fuzz: the input is saved as ";
  write_all(2, saved, std::strlen(saved));
  write_all(2, g_finding_path.c_str(), g_finding_path.size());
  write_all(2, "\n", 1);
  _exit(1);
}

void install_handlers() {
  // Its own stack, so that a stack overflow can still be reported.
  static std::vector<char> stack(1 << 16);
  stack_t ss{};
  ss.ss_sp = stack.data();
  ss.ss_size = stack.size();
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sa.sa_flags = SA_ONSTACK;
  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL, SIGALRM}) sigaction(sig, &sa, nullptr);
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Runs one input; exits 1 on a finding.
void run_one(const std::string& input, unsigned timeout) {
  g_input = &input;
  alarm(timeout);
  try {
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
  } catch (const std::exception& e) {
    alarm(0);
    save_input();
    std::fprintf(stderr,
                 "\nvesper fuzz: FINDING: uncaught %s: %s\nvesper fuzz: the input is saved as %s\n",
                 typeid(e).name(), e.what(), g_finding_path.c_str());
    std::exit(1);
  } catch (...) {
    alarm(0);
    save_input();
    std::fprintf(stderr,
                 "\nvesper fuzz: FINDING: uncaught non-std exception\nvesper fuzz: the input is "
                 "saved as %s\n",
                 g_finding_path.c_str());
    std::exit(1);
  }
  alarm(0);
  g_input = nullptr;
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--seconds")
      o.seconds = std::stod(value());
    else if (a == "--runs")
      o.runs = std::stoll(value());
    else if (a == "--seed")
      o.seed = std::stoull(value());
    else if (a == "--timeout")
      o.timeout = unsigned(std::stoul(value()));
    else if (a == "--artifacts")
      o.artifacts = value();
    else if (fs::is_directory(a))
      o.corpus_dirs.push_back(a);
    else if (fs::is_regular_file(a))
      o.files.push_back(a);
    else {
      std::fprintf(stderr, "unknown option or missing path: %s\n", a.c_str());
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_args(argc, argv);
  const std::string target = fs::path(argv[0]).filename().string();
  g_finding_path = (o.artifacts / (target + "-finding")).string();
  install_handlers();

  if (!o.files.empty()) {  // reproduce
    for (const fs::path& f : o.files) {
      std::fprintf(stderr, "%s: running %s\n", target.c_str(), f.c_str());
      run_one(read_file(f), o.timeout);
    }
    std::fprintf(stderr, "%s: %zu inputs, no finding\n", target.c_str(), o.files.size());
    return 0;
  }

  std::vector<std::string> seeds;
  for (const fs::path& dir : o.corpus_dirs) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());  // the same order on every machine
    for (const fs::path& f : files) seeds.push_back(read_file(f));
  }
  if (seeds.empty()) seeds.push_back("{}");
  vesper::fuzz::Mutator mutator(o.seed, vesper::fuzz::json_dictionary(seeds));

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  long long runs = 0;
  for (const std::string& s : seeds) run_one(s, o.timeout), ++runs;
  const long long seeds_accepted = vesper::fuzz::accepted_count();

  std::vector<std::string> pool = seeds;  // starting points: seeds + accepted mutants
  const size_t kPoolMax = 512;
  while (elapsed() < o.seconds && (o.runs == 0 || runs < o.runs)) {
    const std::string& base = pool[mutator.next(pool.size())];
    std::string input = mutator.mutate(base, pool);
    const long long before = vesper::fuzz::accepted_count();
    run_one(input, o.timeout);
    ++runs;
    if (vesper::fuzz::accepted_count() > before) {
      if (pool.size() < kPoolMax)
        pool.push_back(std::move(input));
      else
        pool[seeds.size() + mutator.next(kPoolMax - seeds.size())] = std::move(input);
    }
  }
  const double t = elapsed();
  std::printf(
      "%s: %lld runs (%zu seeds, %lld accepted) in %.1f s, %.0f runs/s; %lld mutated "
      "inputs accepted by the parser; seed %llu; 0 findings\n",
      target.c_str(), runs, seeds.size(), seeds_accepted, t, double(runs) / t,
      vesper::fuzz::accepted_count() - seeds_accepted, (unsigned long long)o.seed);
  return 0;
}

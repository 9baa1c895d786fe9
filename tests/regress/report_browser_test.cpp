// The HTML report in a real browser (headless Chromium, Debian `chromium`):
// it loads without a console message, every picture decodes, and the DOM
// shows the verdicts of a passing, a regressed and an error scene. The page
// and a screenshot stay in the build tree (printed) for a human to look at.
// Skipped when no Chromium is installed (scripts/setup installs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <regex>

#include "regress/report_html.h"
#include "tests/common/background_process.h"
#include "tests/common/temp_dir.h"
#include "tests/regress/report_fixtures.h"
#include "tests/regress/report_test_util.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

// $VESPER_CHROMIUM, else the first of the usual names on PATH; empty if none.
std::string find_chromium() {
  if (const char* env = std::getenv("VESPER_CHROMIUM"); env && *env) return env;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    size_t start = 0;
    while (start <= dirs.size()) {
      const size_t end = std::min(dirs.find(':', start), dirs.size());
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
      start = end + 1;
    }
  }
  return "";
}

// Appended to a copy of the page (never the page itself, which has no
// script): after load, every picture that did not decode is a console
// error, and the count of those that did lands in the DOM.
constexpr const char* kImageCheck = R"js(<script>
window.addEventListener("load", () => {
  let decoded = 0;
  for (const img of document.images) {
    if (img.complete && img.naturalWidth > 0) ++decoded;
    else console.error("picture did not load: " + img.getAttribute("src"));
  }
  document.body.setAttribute("data-pictures-decoded", String(decoded));
});
</script></body>)js";

std::string with_before_body_end(std::string html, const std::string& insert) {
  const size_t at = html.rfind("</body>");
  return html.replace(at, 7, insert);
}

// Chromium's own log lines for page console messages ("INFO:CONSOLE(..)",
// "ERROR:CONSOLE"), and uncaught exceptions.
std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> lines;
  static const std::regex console(R"re(:CONSOLE|Uncaught)re");
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, console)) lines.push_back(line);
  return lines;
}

struct BrowserRun {
  fs::path dom, log;
  std::unique_ptr<BackgroundProcess> process;
};

// `extra` flags before the URL (--screenshot=...); a fresh profile per run so
// two can run at once.
BrowserRun start_chromium(const std::string& chromium, const fs::path& page, const fs::path& work,
                          const std::string& name, const std::vector<std::string>& extra) {
  BrowserRun run{work / (name + ".dom.html"), work / (name + ".log"), nullptr};
  std::vector<std::string> argv{chromium,
                                "--headless",
                                "--disable-gpu",
                                "--no-sandbox",
                                "--no-first-run",
                                "--disable-extensions",
                                "--disable-background-networking",
                                "--user-data-dir=" + (work / (name + "-profile")).string(),
                                "--enable-logging=stderr",
                                "--v=0",
                                "--dump-dom"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  argv.push_back("file://" + fs::absolute(page).string());
  run.process = std::make_unique<BackgroundProcess>(argv, run.dom, run.log);
  return run;
}

TEST(ReportBrowser, ChromiumShowsTheVerdictsWithoutConsoleErrors) {
  const std::string chromium = find_chromium();
  if (chromium.empty()) GTEST_SKIP() << "no chromium on PATH (Debian package `chromium`)";
  TempDir work("regress-browser");
  const ReportFixture fixture = make_report_fixture(work.path());
  const fs::path artifacts = fs::path(VESPER_TEST_ARTIFACT_DIR);
  const fs::path report = artifacts / "report";
  fs::create_directories(report);
  regress::write_report_html(fixture.run, &fixture.history, report);
  const std::string html = read_text(report / "index.html");
  // Copies beside the page, so its relative picture paths resolve.
  const fs::path checked = report / ".browser-check.html", broken = report / ".browser-broken.html";
  std::ofstream(checked) << with_before_body_end(html, kImageCheck);
  std::ofstream(broken) << with_before_body_end(html,
                                                "<script>notDefinedAnywhere();</script></body>");

  const fs::path screenshot = artifacts / "report-screenshot.png";
  BrowserRun good =
      start_chromium(chromium, checked, work.path(), "good",
                     {"--window-size=1280,2600", "--screenshot=" + screenshot.string()});
  BrowserRun bad = start_chromium(chromium, broken, work.path(), "bad", {});
  ASSERT_EQ(good.process->wait_for(90), 0) << read_text(good.log);
  ASSERT_EQ(bad.process->wait_for(90), 0) << read_text(bad.log);
  fs::remove(checked);
  fs::remove(broken);

  // The detector sees an injected error, so its silence on the page means something.
  const std::vector<std::string> injected = console_lines(read_text(bad.log));
  ASSERT_FALSE(injected.empty()) << "the console check missed an injected error:\n"
                                 << read_text(bad.log);
  EXPECT_NE(injected[0].find("notDefinedAnywhere"), std::string::npos) << injected[0];

  EXPECT_EQ(console_lines(read_text(good.log)), std::vector<std::string>{});
  const std::string dom = read_text(good.dom);
  EXPECT_NE(dom.find("data-pictures-decoded=\"12\""), std::string::npos)
      << "every picture decodes: " << dom.substr(dom.find("<body"), 120);
  const std::string pass = section_of(dom, "scene-0-h", "</h2>");
  const std::string regressed = section_of(dom, "scene-1-h", "</h2>");
  const std::string error = section_of(dom, "scene-2-h", "</h2>");
  EXPECT_NE(pass.find("Scene cornell"), std::string::npos) << pass;
  EXPECT_NE(pass.find("PASS"), std::string::npos) << pass;
  EXPECT_NE(regressed.find("Scene cornell-red-wall"), std::string::npos) << regressed;
  EXPECT_NE(regressed.find("REGRESSED"), std::string::npos) << regressed;
  EXPECT_NE(error.find("ERROR"), std::string::npos) << error;
  EXPECT_NE(dom.find("could have detected changes"), std::string::npos);
  ASSERT_TRUE(fs::is_regular_file(screenshot));
  EXPECT_GT(fs::file_size(screenshot), 10000u);
  std::cout << "report: " << (report / "index.html").string()
            << "\nscreenshot: " << screenshot.string() << std::endl;
}

}  // namespace
}  // namespace vesper::test

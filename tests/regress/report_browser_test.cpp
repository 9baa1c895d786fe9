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
#include "tests/common/chromium.h"
#include "tests/common/temp_dir.h"
#include "tests/regress/report_fixtures.h"
#include "tests/regress/report_test_util.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;

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

// A file page in Chromium (tests/common/chromium.h).
BrowserRun start_on_file(const std::string& chromium, const fs::path& page, const fs::path& work,
                         const std::string& name, const std::vector<std::string>& extra) {
  return test::start_chromium(chromium, "file://" + fs::absolute(page).string(), work, name, extra);
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
      start_on_file(chromium, checked, work.path(), "good",
                    {"--window-size=1280,2600", "--screenshot=" + screenshot.string()});
  BrowserRun bad = start_on_file(chromium, broken, work.path(), "bad", {});
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

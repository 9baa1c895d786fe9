// The HTML report as a file: self-contained, every picture there and the
// render's size, the verdicts, reasons, regions and trends where a reader
// looks for them, and a rewrite that never leaves a half page.
#include "regress/report_html.h"

#include "regress/html_text.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <memory>
#include <regex>

#include "tests/common/temp_dir.h"
#include "tests/regress/report_fixtures.h"
#include "tests/regress/report_test_util.h"

namespace vesper::test {
namespace {

namespace fs = std::filesystem;
using regress::write_report_html;

class ReportHtml : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    renders_ = std::make_unique<TempDir>("regress-renders");
    fixture_ = std::make_unique<ReportFixture>(make_report_fixture(renders_->path()));
  }
  static void TearDownTestSuite() {
    fixture_.reset();
    renders_.reset();
  }
  // Writes the fixture's report into this test's folder and returns the page.
  std::string write_page() {
    write_report_html(fixture_->run, &fixture_->history, dir_.path());
    return read_text(dir_ / "index.html");
  }

  static std::unique_ptr<TempDir> renders_;
  static std::unique_ptr<ReportFixture> fixture_;
  TempDir dir_{"regress-report"};
};
std::unique_ptr<TempDir> ReportHtml::renders_;
std::unique_ptr<ReportFixture> ReportHtml::fixture_;

TEST_F(ReportHtml, PageIsSelfContained) {
  const std::string html = write_page();
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  EXPECT_EQ(count_of(html, "url("), count_of(html, "url(#")) << "only in-page references";
  const std::vector<std::string> srcs = src_attributes(html);
  EXPECT_EQ(srcs.size(), 12u) << "golden, new, difference, significance for 3 compared scenes";
  for (const std::string& src : srcs) {
    EXPECT_EQ(src.rfind("img/", 0), 0u) << src;
    EXPECT_TRUE(fs::is_regular_file(dir_ / src)) << src;
  }
}

TEST_F(ReportHtml, PicturesArePngsOfTheRenderSize) {
  const std::string html = write_page();
  for (const std::string& src : src_attributes(html)) {
    auto in = OIIO::ImageInput::open((dir_ / src).string());
    ASSERT_TRUE(in) << src;
    EXPECT_STREQ(in->format_name(), "png");
    EXPECT_EQ(in->spec().width, 64) << src;
    EXPECT_EQ(in->spec().height, 48) << src;
  }
}

TEST_F(ReportHtml, TopShowsOverallVerdictDateVersionSuiteAndCounts) {
  const std::string html = write_page();
  const std::string header = html.substr(0, html.find("</header>"));
  EXPECT_NE(header.find("class=\"overall v-error\""), std::string::npos);
  EXPECT_NE(header.find(" ERROR</span>"), std::string::npos) << "the verdict in words";
  EXPECT_NE(header.find("2024-05-07T02:00:00Z"), std::string::npos);
  EXPECT_NE(header.find("vesper 0.13.0 (test)"), std::string::npos);
  EXPECT_NE(header.find(fixture_->run.suite), std::string::npos);
  EXPECT_NE(header.find("4 (2 pass, 1 regressed, 1 error)"), std::string::npos);
  EXPECT_NE(html.find("<title>error &mdash;"), std::string::npos);
}

TEST_F(ReportHtml, SceneTableHasVerdictReasonsAndTiming) {
  const std::string html = write_page();
  const size_t a = html.find("<table class=\"scenes\">");
  ASSERT_NE(a, std::string::npos);
  const std::string rows = html.substr(a, html.find("</table>", a) - a);
  EXPECT_NE(rows.find("PASS</span></td><th scope=\"row\"><a href=\"#scene-0\">cornell</a>"),
            std::string::npos);
  EXPECT_NE(rows.find("REGRESSED</span></td><th scope=\"row\"><a href=\"#scene-1\">"
                      "cornell-red-wall</a>"),
            std::string::npos);
  EXPECT_NE(
      rows.find("beauty: " + std::to_string(fixture_->run.scenes[1].layers[0].significant_tiles) +
                " tiles changed beyond noise"),
      std::string::npos);
  EXPECT_NE(rows.find("1.2 s &rarr; 1.25 s (&times;1.04)"), std::string::npos);
  EXPECT_NE(rows.find("reused: not re-rendered"), std::string::npos);
  EXPECT_NE(rows.find("no golden: "), std::string::npos);
}

TEST_F(ReportHtml, ErrorSceneShowsItsReasonInAnAlert) {
  const std::string html = write_page();
  const std::string scene = section_of(html, "scene-2", "id=\"scene-3\"");
  const size_t alert = scene.find("role=\"alert\"");
  ASSERT_NE(alert, std::string::npos);
  EXPECT_NE(scene.find("missing-golden.exr does not exist (write it with --update-goldens)", alert),
            std::string::npos);
  EXPECT_NE(scene.find("ERROR</span></h2>"), std::string::npos);
}

TEST_F(ReportHtml, PassSceneSaysHowStrongTheTestWas) {
  const std::string html = write_page();
  const std::string scene = section_of(html, "scene-0", "id=\"scene-1\"");
  const double mdc = fixture_->run.scenes[0].layers[0].min_detectable_change;
  ASSERT_GT(mdc, 0);
  EXPECT_NE(scene.find("could have detected changes &ge; " + regress::format_percent(mdc)),
            std::string::npos)
      << scene.substr(0, 2000);
}

TEST_F(ReportHtml, RegressedSceneOutlinesAndListsItsWorstRegions) {
  const std::string html = write_page();
  const std::string scene = section_of(html, "scene-1", "id=\"scene-2\"");
  const auto& worst = fixture_->run.scenes[1].layers[0].worst;
  ASSERT_FALSE(worst.empty()) << "a 25 % brighter wall must be found by the fixture's test";
  EXPECT_EQ(count_of(scene, "class=\"region-inner\""), worst.size());
  EXPECT_NE(scene.find(fmt::format("{}, {}, {} &times; {}", worst[0].x, worst[0].y, worst[0].width,
                                   worst[0].height)),
            std::string::npos);
  EXPECT_NE(scene.find("brighter)"), std::string::npos);
  EXPECT_NE(scene.find("Luminosity histograms of beauty: golden vs new"), std::string::npos);
}

TEST_F(ReportHtml, EveryPictureAndChartHasATextAlternative) {
  const std::string html = write_page();
  static const std::regex img(R"re(<img [^>]*>)re"), alt(R"re(\balt="[^"]+")re");
  size_t images = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator();
       ++it, ++images)
    EXPECT_TRUE(std::regex_search(it->str(), alt)) << it->str();
  EXPECT_EQ(images, 12u);
  const size_t charts = count_of(html, "<svg class=\"chart\"");
  EXPECT_EQ(charts, 3u * 4 + 3) << "3 trend charts per scene, a histogram per compared layer";
  EXPECT_EQ(count_of(html, "role=\"img\" aria-labelledby="), charts);
  EXPECT_EQ(count_of(html, "<desc id="), charts);
  EXPECT_EQ(count_of(html, "<html lang=\"en\">"), 1u);
}

TEST_F(ReportHtml, TrendChartsShowEveryRunOfTheHistory) {
  const std::string html = write_page();
  const std::string scene = section_of(html, "scene-0", "id=\"scene-1\"");
  const std::string time_chart = section_of(scene, "scene-0-time-t", "</svg>");
  ASSERT_FALSE(time_chart.empty());
  EXPECT_EQ(count_of(time_chart, "<title>2024-"), 7u) << "six earlier runs and this one";
  EXPECT_NE(time_chart.find("2024-05-07T02:00:00Z: 1.22 s, pass"), std::string::npos);
  EXPECT_NE(scene.find("Across runs (7 kept in the history)"), std::string::npos);
}

TEST_F(ReportHtml, RewriteReplacesThePageAndRemovesTheOldPictures) {
  write_page();
  const std::string second = write_page();
  std::vector<fs::path> folders;
  for (const auto& e : fs::directory_iterator(dir_ / "img")) folders.push_back(e.path());
  ASSERT_EQ(folders.size(), 1u);
  EXPECT_NE(second.find("img/" + folders[0].filename().string() + "/"), std::string::npos);
  for (const auto& e : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(ReportHtml, AFailedWriteLeavesThePreviousReportWhole) {
  const std::string first = write_page();
  // The page's temporary name taken by a non-empty folder: the write fails.
  const fs::path blocker = dir_ / fmt::format(".index.html.tmp-{}", ::getpid());
  fs::create_directories(blocker / "x");
  EXPECT_THROW(write_report_html(fixture_->run, &fixture_->history, dir_.path()),
               regress::ReportError);
  EXPECT_EQ(read_text(dir_ / "index.html"), first);
  for (const std::string& src : src_attributes(first))
    EXPECT_TRUE(fs::is_regular_file(dir_ / src)) << "the old page's pictures stay: " << src;
  size_t folders = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_ / "img")) ++folders;
  EXPECT_EQ(folders, 1u) << "the failed run's pictures are removed";
}

TEST_F(ReportHtml, WorksWithoutHistoryAndForAnEmptyRun) {
  write_report_html(fixture_->run, nullptr, dir_.path());
  EXPECT_NE(read_text(dir_ / "index.html").find("Across runs (1 kept in the history)"),
            std::string::npos);
  regress::RunResult empty;
  write_report_html(empty, nullptr, dir_.path());
  EXPECT_NE(read_text(dir_ / "index.html").find("0 (0 pass, 0 regressed, 0 error)"),
            std::string::npos);
}

}  // namespace
}  // namespace vesper::test

#include "regress/report_html.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>

#include "common/atomic_file.h"
#include "regress/html_text.h"
#include "regress/report_images.h"
#include "regress/report_sections.h"
#include "regress/report_style.h"
#include "regress/trend_chart.h"

namespace vesper::regress {

namespace fs = std::filesystem;

namespace {

constexpr const char* kImageFolderPrefix = "run-";

struct VerdictCounts {
  size_t pass = 0, regressed = 0, error = 0;
};

VerdictCounts count_verdicts(const RunResult& run) {
  VerdictCounts c;
  for (const SceneResult& s : run.scenes)
    (s.verdict == Verdict::Pass        ? c.pass
     : s.verdict == Verdict::Regressed ? c.regressed
                                       : c.error)++;
  return c;
}

std::string counts_text(const VerdictCounts& c) {
  return fmt::format("{} pass, {} regressed, {} error", c.pass, c.regressed, c.error);
}

std::string page_head(const RunResult& run) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
      "<title>{} &mdash; Vesper regression report, {}</title><style>{}</style></head>\n",
      verdict_name(run.verdict), html_escape(run.started_at), report_css());
}

std::string page_header(const RunResult& run) {
  const VerdictCounts c = count_verdicts(run);
  std::string s = "<header><h1>Vesper regression report</h1>";
  s += "<p role=\"status\">" + verdict_badge(run.verdict, "overall") + "</p>";
  s += fmt::format(
      "<dl class=\"facts\"><dt>Run started</dt><dd><time datetime=\"{0}\">{0}</time></dd>"
      "<dt>Renderer</dt><dd>{1}</dd><dt>Suite</dt><dd><code>{2}</code></dd>"
      "<dt>Scenes</dt><dd>{3} ({4})</dd><dt>Rendered</dt><dd>{5}</dd>",
      html_escape(run.started_at), html_escape(run.renderer_version), html_escape(run.suite),
      run.scenes.size(), counts_text(c),
      run.server.empty() ? std::string("here (--local)")
                         : "on the farm at <code>" + html_escape(run.server) + "</code>");
  if (!run.render_time_note.empty())
    s += "<dt>Render times</dt><dd>" + html_escape(run.render_time_note) + "</dd>";
  return s + "</dl></header>\n";
}

// Scene-level reasons, then each layer's prefixed with the layer.
std::string all_reasons(const SceneResult& scene) {
  std::string s;
  for (const std::string& r : scene.reasons) s += "<li>" + html_escape(r) + "</li>";
  for (const LayerResult& layer : scene.layers)
    for (const std::string& r : layer.reasons)
      s += "<li>" + html_escape(layer.layer + ": " + r) + "</li>";
  return s.empty() ? "&mdash;" : "<ul>" + s + "</ul>";
}

std::string scenes_table(const RunResult& run) {
  std::string s =
      "<table class=\"scenes\"><caption>Scenes</caption><thead><tr><th scope=\"col\">Verdict</th>"
      "<th scope=\"col\">Scene</th><th scope=\"col\">Reasons</th><th scope=\"col\">Render time "
      "golden &rarr; new</th></tr></thead><tbody>";
  for (size_t i = 0; i < run.scenes.size(); ++i) {
    const SceneResult& scene = run.scenes[i];
    s += fmt::format(
        "<tr class=\"{}\"><td>{}</td><th scope=\"row\"><a href=\"#{}\">{}</a></th><td>{}</td>"
        "<td class=\"num\">{}</td></tr>",
        verdict_class(scene.verdict), verdict_badge(scene.verdict), scene_anchor(i),
        html_escape(scene.name), all_reasons(scene), render_time_text(scene));
  }
  return s + "</tbody></table>\n";
}

std::string page(const RunResult& run, const std::vector<TrendPoint>* trends,
                 const ReportImages& images) {
  std::string s = page_head(run) + "<body>" + page_header(run) + "<main>" + scenes_table(run);
  for (size_t i = 0; i < run.scenes.size(); ++i)
    s += scene_section(run.scenes[i], i, images, scene_trend(trends, run, run.scenes[i].name)) +
         "\n";
  s += "</main><footer><p>Written by <code>vesper regress</code>. Self-contained: the pictures "
       "are beside this page, nothing is fetched from the network.";
  if (!images.display_note().empty()) s += " " + html_escape(images.display_note()) + ".";
  return s + "</p></footer></body></html>\n";
}

// A folder name no earlier report in DIR used: the run's start, the process
// and a counter (two reports of one run in one process stay apart).
std::string image_folder_name(const RunResult& run) {
  static std::atomic<unsigned> counter{0};
  std::string stamp;
  for (char c : run.started_at)
    if (std::isalnum(static_cast<unsigned char>(c))) stamp += c;
  return fmt::format("{}{}-{}-{}", kImageFolderPrefix, stamp.empty() ? "unknown" : stamp,
                     ::getpid(), counter++);
}

// Earlier reports' picture folders (ours only: named run-*), now unreferenced.
void remove_old_image_folders(const fs::path& img, const std::string& keep) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(img, ec)) {
    const std::string name = e.path().filename().string();
    if (name != keep && name.rfind(kImageFolderPrefix, 0) == 0 && e.is_directory(ec))
      fs::remove_all(e.path(), ec);  // best effort: a leftover only costs space
  }
}

}  // namespace

void write_report_html(const RunResult& run, const std::vector<TrendPoint>* trends,
                       const fs::path& dir) {
  const std::string folder = image_folder_name(run);
  const fs::path relative = fs::path("img") / folder;
  std::error_code ec;
  fs::create_directories(dir / relative, ec);
  if (ec) throw ReportError(dir.string() + ": cannot create the report folder: " + ec.message());
  try {
    const ReportImages images(dir, relative);
    write_file_atomically(dir / "index.html", page(run, trends, images));
  } catch (const FileWriteError& e) {
    fs::remove_all(dir / relative, ec);
    throw ReportError(e.what());
  } catch (const std::exception& e) {
    fs::remove_all(dir / relative, ec);
    throw ReportError(dir.string() + ": cannot write the report: " + e.what());
  }
  remove_old_image_folders(dir / "img", folder);
}

}  // namespace vesper::regress

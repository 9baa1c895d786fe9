// vesper fetch (and vesper up): a job's frames into a folder.
#include "cli/fetch.h"

#include <fmt/format.h>

#include "cli/job_watch.h"
#include "common/control_characters.h"
#include "common/sha256.h"
#include "common/utf8.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {

std::string job_file_stem(const std::string& name, long long job) {
  constexpr size_t kMaxStemBytes = 200;  // leaves room for ".####.comp.hist.json" in 255
  std::string stem;
  const std::string text = utf8_safe(name, kMaxStemBytes);
  for (size_t i = 0; i < text.size();) {
    const size_t n = utf8_character_length(text, i);
    const std::string character = text.substr(i, n);
    const bool unsafe = character == "/" || character == "\\" || character == "#" ||
                        !control_character_problem(character).empty() ||
                        (stem.empty() && character == ".");
    stem += unsafe ? "_" : character;
    i += n;
  }
  return stem.empty() ? "job-" + std::to_string(job) : stem;
}

void download_frame(FarmClient& client, long long job, const protocol::FrameInfo& frame,
                    const std::filesystem::path& file) {
  client.download(protocol::frame_path(job, frame.frame), file);
  if (frame.blob.empty()) return;
  const auto sha = sha256_file(file);
  if (!sha || *sha != frame.blob) {
    std::filesystem::remove(file);
    throw FarmClientError(file.string() + ": downloaded frame does not match its hash");
  }
}

FetchedFrames fetch_frames(FarmClient& client, long long job, const std::filesystem::path& dir) {
  const std::string name =
      client.get_json(protocol::job_path(job)).get<protocol::JobSummary>().name;
  const protocol::FrameList frames = wait_for_merges(client, job);
  std::filesystem::create_directories(dir);
  FetchedFrames out;
  out.stem = job_file_stem(name, job);
  out.pattern = (dir / (out.stem + ".####.exr")).string();
  for (const protocol::FrameInfo& f : frames.frames) {
    if (f.state != protocol::FrameState::Ready) {
      out.missing.push_back(f.frame);
      continue;
    }
    const std::filesystem::path file = dir / fmt::format("{}.{:04d}.exr", out.stem, f.frame);
    download_frame(client, job, f, file);
    out.written.push_back(file);
  }
  return out;
}

}  // namespace vesper::cli

// vesper fetch (and vesper up): a job's frames into a folder.
#include "cli/fetch.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "cli/job_watch.h"
#include "common/control_characters.h"
#include "common/sha256.h"
#include "common/utf8.h"
#include "protocol/job_messages.h"
#include "protocol/paths.h"

namespace vesper::cli {
namespace {

// The OpenEXR reader itself opens the header (the file has no meaningful
// extension to go by): junk bytes, a partial render or a PNG are refused.
bool is_openexr_file(const std::filesystem::path& file) {
  auto in = OIIO::ImageInput::create("openexr");
  OIIO::ImageSpec spec;
  const bool ok = in && in->open(file.string(), spec);
  if (!ok) OIIO::geterror();  // no error left pending
  return ok;
}

}  // namespace

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
  // Checked under a temporary name, renamed to `file` only when it passed:
  // a bad frame never appears as an .exr, not even for a moment.
  const std::filesystem::path tmp = file.string() + ".fetch";
  client.download(protocol::frame_path(job, frame.frame), tmp);
  std::string problem;
  if (!frame.blob.empty()) {
    const auto sha = sha256_file(tmp);
    if (!sha || *sha != frame.blob) problem = "downloaded frame does not match its hash";
  }
  // A server that took a worker's junk (an older server, or one with
  // verify_results off) must not make `fetch` save it as an image.
  if (problem.empty() && !is_openexr_file(tmp))
    problem = "frame " + std::to_string(frame.frame) + " of job " + std::to_string(job) +
              " from the server is not an OpenEXR image; not saved";
  if (!problem.empty()) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw FarmClientError(file.string() + ": " + problem);
  }
  std::filesystem::rename(tmp, file);
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

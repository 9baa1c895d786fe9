// Fuzz target: the job file read by `vesper submit` (`vesper-job/1`,
// cli/job_file.h): first the check whether a file is a job file at all
// (which must never throw), then the reader, whose documented error is
// JsonError, then the frame list (FrameRangeError), as submit_job checks it.
#include "cli/job_file.h"
#include "common/json_error.h"
#include "jobs/frame_range.h"
#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  static const std::filesystem::path file = fuzz::sandbox() / "job.json";
  const std::string text = fuzz::text_of(data, size);
  (void)cli::is_job_file_text(text);
  cli::JobRequest defaults;
  defaults.frames = "1";
  try {
    const cli::JobRequest r = cli::parse_job_file_text(text, file, defaults);
    parse_frame_range(r.frames);
  } catch (const JsonError&) {
    return 0;
  } catch (const FrameRangeError&) {
    return 0;
  }
  fuzz::note_accepted();
  return 0;
}

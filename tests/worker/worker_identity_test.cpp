// The id a worker keeps across restarts: one locked slot per running worker
// in the cache dir.
#include "worker/worker_identity.h"

#include <gtest/gtest.h>

#include <memory>

#include "tests/common/temp_dir.h"

namespace vesper::worker_detail {
namespace {

TEST(WorkerIdentity, ARestartedWorkerGetsItsIdBackAndConcurrentOnesDoNotShare) {
  const test::TempDir dir("worker-identity");
  {
    WorkerIdentity first(dir.path());
    EXPECT_EQ(first.saved_id(), "");
    first.save("id-one");
    WorkerIdentity second(dir.path());  // running beside the first: another slot
    EXPECT_EQ(second.saved_id(), "");
    second.save("id-two");
  }
  // Restarted (the locks died with them): the first slot first.
  auto again = std::make_unique<WorkerIdentity>(dir.path());
  EXPECT_EQ(again->saved_id(), "id-one");
  WorkerIdentity beside(dir.path());
  EXPECT_EQ(beside.saved_id(), "id-two");
  again.reset();
  EXPECT_EQ(WorkerIdentity(dir.path()).saved_id(), "id-one");
}

}  // namespace
}  // namespace vesper::worker_detail

// How long a worker retries the calls of a task it holds: a server away
// (transport errors) for longer than the lease, a 5xx until the lease could
// be dead, nothing else.
#include "worker/lease_retry.h"

#include <gtest/gtest.h>

#include <chrono>

namespace vesper::worker_detail {
namespace {

using Clock = std::chrono::steady_clock;

HttpResponse answer(long status) {
  HttpResponse r;
  r.status = status;
  if (status == 0) r.error = "connection refused";
  return r;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

TEST(LeaseRetry, AnUnreachableServerIsWaitedForBeyondTheLease) {
  std::atomic<bool> stop{false};
  LeaseRetry retry(/*lease_seconds=*/0.1, Backoff(0.01, 0.02), stop);
  const auto start = Clock::now();
  int calls = 0;
  const HttpResponse r = retry.call(
      [&] {
        ++calls;
        return seconds_since(start) < 0.4 ? answer(0) : answer(201);
      },
      "upload", 1);
  EXPECT_EQ(r.status, 201);
  EXPECT_FALSE(retry.gave_up());
  EXPECT_GT(calls, 5);
}

TEST(LeaseRetry, AServerErrorIsRetriedUntilTheLeaseCouldBeDead) {
  std::atomic<bool> stop{false};
  LeaseRetry retry(0.3, Backoff(0.01, 0.02), stop);
  const auto start = Clock::now();
  const HttpResponse r = retry.call([] { return answer(503); }, "complete", 1);
  EXPECT_EQ(r.status, 503);
  EXPECT_TRUE(retry.gave_up());
  EXPECT_GE(seconds_since(start), 0.25);
  EXPECT_LT(seconds_since(start), 5);
  // A heartbeat the server accepted renews the lease: worth retrying again.
  retry.confirmed();
  int calls = 0;
  EXPECT_EQ(retry.call([&] { return answer(++calls < 3 ? 500 : 200); }, "c", 1).status, 200);
  EXPECT_FALSE(retry.gave_up());
}

TEST(LeaseRetry, RefusalsAreAnswersAndStopEndsTheRetries) {
  std::atomic<bool> stop{false};
  LeaseRetry retry(60, Backoff(0.01, 0.02), stop);
  for (long status : {200L, 400L, 404L, 409L, 413L}) {
    int calls = 0;
    EXPECT_EQ(retry.call([&] { return ++calls, answer(status); }, "x", 1).status, status);
    EXPECT_EQ(calls, 1);
    EXPECT_FALSE(retry.gave_up());
  }
  int calls = 0;
  const HttpResponse r = retry.call(
      [&] {
        if (++calls == 3) stop = true;
        return answer(0);
      },
      "upload", 1);
  EXPECT_EQ(r.status, 0);
  EXPECT_TRUE(retry.gave_up());
  EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace vesper::worker_detail

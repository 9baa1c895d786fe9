// AtomicExactSum (output/atomic_exact_sum.h): three carry-free limbs add up
// to exactly the ExactSum of the same values, from any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "renderer/output/atomic_exact_sum.h"
#include "renderer/sampling/sampler.h"

namespace vesper::test {
namespace {

// Values over the whole range to_fixed keeps: negative and positive, from
// below 2^-41 (truncated) to the clamp at 2^40 and beyond.
std::vector<float> values(size_t n) {
  std::vector<float> v;
  Sampler s(uint64_t(17));
  for (size_t i = 0; i < n; ++i) {
    const float mag = std::ldexp(1.f + s.next1(), int(s.next1() * 100.f) - 50);
    v.push_back(s.next1() < 0.5f ? -mag : mag);
  }
  v.push_back(3e12f);  // clamped to 2^40
  v.push_back(-3e12f);
  v.push_back(1e-20f);  // truncated to 0
  return v;
}

TEST(AtomicExactSum, EqualsTheExactSumOfTheSameValues) {
  ExactSum plain = 0;
  AtomicExactSum atomic;
  for (float x : values(100000)) {
    plain += to_fixed(x);
    atomic.add(to_fixed(x));
  }
  EXPECT_TRUE(atomic.load() == plain);
  EXPECT_FALSE(plain == 0);
}

TEST(AtomicExactSum, IsTheSameFromTwoThreads) {
  const std::vector<float> v = values(200000);
  ExactSum plain = 0;
  for (float x : v) plain += to_fixed(x);
  AtomicExactSum atomic;
  auto add_every_other = [&](size_t first) {
    for (size_t i = first; i < v.size(); i += 2) atomic.add(to_fixed(v[i]));
  };
  std::thread a(add_every_other, 0), b(add_every_other, 1);
  a.join();
  b.join();
  EXPECT_TRUE(atomic.load() == plain);
}

TEST(AtomicExactSum, HoldsTheLargestValuesNegativeAndPositive) {
  // 2^20 clamped samples of either sign: a's limb carries them all.
  AtomicExactSum up, down;
  const ExactSum big = to_fixed(std::ldexp(1.f, 45));
  for (int i = 0; i < (1 << 20); ++i) {
    up.add(big);
    down.add(-big);
  }
  EXPECT_TRUE(up.load() == big * (1 << 20));
  EXPECT_TRUE(down.load() == -big * (1 << 20));
}

}  // namespace
}  // namespace vesper::test

#pragma once
// An ExactSum (exact_sum.h) that threads add to concurrently. Integer
// addition is associative, so the total is the same bits whatever the order
// and the thread count. 128-bit atomics are not lock-free on x86-64 (GCC
// sends them to libatomic's locks), so the fixed-point value F is split into
// three limbs, each summed in a lock-free int64 without carries:
// F = a * 2^70 + b * 2^35 + c, with b and c in [0, 2^35) and |a| <= 2^34
// (|F| <= 2^104 after to_fixed's clamp). Up to kMaxAtomicExactAdds
// additions keep every limb's sum below 2^63.
#include <atomic>
#include <cstdint>

#include "renderer/output/exact_sum.h"

namespace vesper {

inline constexpr int64_t kMaxAtomicExactAdds = int64_t(1) << 28;

class AtomicExactSum {
 public:
  void add(ExactSum f) {
    __extension__ typedef unsigned __int128 Bits;
    const Bits u = Bits(f);
    c_.fetch_add(int64_t(u & kLimbMask), std::memory_order_relaxed);
    b_.fetch_add(int64_t((u >> kLimbBits) & kLimbMask), std::memory_order_relaxed);
    a_.fetch_add(int64_t(f >> (2 * kLimbBits)), std::memory_order_relaxed);
  }
  // The sum; call once every add has happened.
  ExactSum load() const {
    return (ExactSum(a_.load()) << (2 * kLimbBits)) + (ExactSum(b_.load()) << kLimbBits) +
           ExactSum(c_.load());
  }

 private:
  static constexpr int kLimbBits = 35;
  static constexpr uint64_t kLimbMask = (uint64_t(1) << kLimbBits) - 1;
  std::atomic<int64_t> a_{0}, b_{0}, c_{0};
};

}  // namespace vesper

#pragma once
// Sample ranges merge exactly: the sums of [0, split) and [split, spp)
// renders add up to the full render's, bit for bit. And a render is the same
// for one thread and two.
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/render/render.h"

namespace vesper::test {

// `options` renders the full range (its spp, or the scene's); keep_sums is
// set here. Stream sums (variance AOVs, layer_variance) must merge too.
inline void expect_ranges_merge_bitwise(const Scene& scene, RenderOptions options, int split) {
  options.keep_sums = true;
  RenderOptions first = options, second = options;
  first.sample_end = split;
  second.sample_begin = split;
  const RenderResult f = render(scene, options), a = render(scene, first),
                     b = render(scene, second);
  ASSERT_EQ(a.film.sums.size(), f.film.sums.size());
  for (size_t i = 0; i < f.film.sums.size(); ++i)
    ASSERT_TRUE(a.film.sums[i] + b.film.sums[i] == f.film.sums[i]) << i;
  ASSERT_EQ(a.film.stream_sums.size(), f.film.stream_sums.size());
  for (size_t i = 0; i < f.film.stream_sums.size(); ++i)
    ASSERT_TRUE(a.film.stream_sums[i] + b.film.stream_sums[i] == f.film.stream_sums[i]) << i;
}

// Renders `options` on one thread and on two: the same bits. Returns the image.
inline LayeredImage expect_same_bits_on_one_and_two_threads(const Scene& scene,
                                                            RenderOptions options) {
  options.threads = 1;
  const RenderResult a = render(scene, options);
  options.threads = 2;
  const RenderResult b = render(scene, options);
  EXPECT_EQ(a.image.pixels.size(), b.image.pixels.size());
  if (a.image.pixels.size() == b.image.pixels.size()) {
    EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(),
                             a.image.pixels.size() * sizeof(float)));
  }
  return a.image;
}

}  // namespace vesper::test

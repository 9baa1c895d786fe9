#include "regress/colour_ramp.h"

#include <fmt/format.h>

#include <algorithm>

namespace vesper::regress {

namespace {

// matplotlib's viridis sampled at ninths.
constexpr std::array<RampStop, 9> kViridis{{{0.0, {68, 1, 84}},
                                            {0.125, {71, 44, 122}},
                                            {0.25, {59, 81, 139}},
                                            {0.375, {44, 113, 142}},
                                            {0.5, {33, 144, 141}},
                                            {0.625, {39, 173, 129}},
                                            {0.75, {92, 200, 99}},
                                            {0.875, {170, 220, 50}},
                                            {1.0, {253, 231, 37}}}};

// ColorBrewer RdBu (5 classes), blue at the dark end.
constexpr std::array<RampStop, 5> kDiverging{{{0.0, {33, 102, 172}},
                                              {0.25, {103, 169, 207}},
                                              {0.5, {247, 247, 247}},
                                              {0.75, {239, 138, 98}},
                                              {1.0, {178, 24, 43}}}};

}  // namespace

std::span<const RampStop> viridis_stops() { return kViridis; }
std::span<const RampStop> diverging_stops() { return kDiverging; }

std::array<float, 3> ramp_colour(std::span<const RampStop> ramp, double t) {
  t = std::clamp(t, 0.0, 1.0);
  size_t i = 1;
  while (i + 1 < ramp.size() && ramp[i].t < t) ++i;
  const RampStop& a = ramp[i - 1];
  const RampStop& b = ramp[i];
  const double u = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
  std::array<float, 3> out{};
  for (size_t c = 0; c < 3; ++c)
    out[c] = float((a.colour[c] + u * (double(b.colour[c]) - a.colour[c])) / 255.0);
  return out;
}

std::string css_colour(const Rgb8& c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

}  // namespace vesper::regress

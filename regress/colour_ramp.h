#pragma once
// The report's colour ramps, as stops so the PNGs (per pixel) and the SVG
// legends (gradient stops) use exactly the same colours.
// - viridis: perceptually uniform and monotonic in lightness, so the
//   difference heat map still reads in grey and for most colour-blind readers;
// - diverging: blue (darker than the golden) through a light neutral to red
//   (brighter), ColorBrewer's RdBu, for the signed significance map.
#include <array>
#include <cstdint>
#include <span>
#include <string>

namespace vesper::regress {

using Rgb8 = std::array<uint8_t, 3>;

struct RampStop {
  double t;  // position in [0, 1]
  Rgb8 colour;
};

std::span<const RampStop> viridis_stops();
std::span<const RampStop> diverging_stops();  // 0 = most darker, 0.5 = none, 1 = most brighter

// The ramp's colour at t (clamped to [0, 1]), linearly between stops, as
// display-referred floats in [0, 1].
std::array<float, 3> ramp_colour(std::span<const RampStop> ramp, double t);

// "#rrggbb" for CSS and SVG.
std::string css_colour(const Rgb8& c);

}  // namespace vesper::regress

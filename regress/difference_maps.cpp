#include "regress/difference_maps.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "compositor/histogram.h"
#include "regress/colour_ramp.h"

namespace vesper::regress {

namespace {

constexpr std::array<float, 3> kNonFinite{1.f, 0.f, 1.f};  // magenta: not on either ramp

void set_rgb(RgbaImage& img, int x, int y, const std::array<float, 3>& c) {
  for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[size_t(k)];
  img.at(x, y, 3) = 1.f;
}

double luma(const RgbaImage& img, int x, int y) {
  return luminance(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2), LumaWeights::Rec709);
}

// The value at the q-quantile of the finite differences (0 if none).
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  const size_t k = std::min(values.size() - 1, size_t(q * double(values.size())));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
  return values[k];
}

bool tile_grid_ok(const LayerResult& layer) {
  return layer.tile_size > 0 && layer.tiles_x > 0 && layer.tiles_y > 0 &&
         layer.tile_z.size() == size_t(layer.tiles_x) * size_t(layer.tiles_y);
}

}  // namespace

HeatMap difference_heat_map(const RgbaImage& golden, const RgbaImage& fresh) {
  if (golden.width != fresh.width || golden.height != fresh.height)
    throw std::invalid_argument("difference_heat_map: the images differ in size");
  HeatMap map{RgbaImage(golden.width, golden.height)};
  std::vector<double> diff(golden.pixel_count(), std::nan(""));
  std::vector<double> finite;
  finite.reserve(diff.size());
  for (int y = 0; y < golden.height; ++y)
    for (int x = 0; x < golden.width; ++x) {
      const double d = std::fabs(luma(fresh, x, y) - luma(golden, x, y));
      if (!std::isfinite(d)) continue;
      diff[size_t(y) * size_t(golden.width) + size_t(x)] = d;
      finite.push_back(d);
    }
  map.top = quantile(finite, 0.99);
  if (map.top <= 0 && !finite.empty()) map.top = *std::max_element(finite.begin(), finite.end());
  if (map.top <= 0) map.top = 1e-6;  // identical: everything at the bottom of the ramp
  for (int y = 0; y < golden.height; ++y)
    for (int x = 0; x < golden.width; ++x) {
      const double d = diff[size_t(y) * size_t(golden.width) + size_t(x)];
      if (std::isnan(d)) ++map.nonfinite;
      set_rgb(map.image, x, y,
              std::isnan(d) ? kNonFinite : ramp_colour(viridis_stops(), d / map.top));
    }
  return map;
}

std::vector<uint8_t> significant_tile_mask(const LayerResult& layer) {
  if (!tile_grid_ok(layer)) return {};
  if (layer.tile_significant.size() == layer.tile_z.size()) return layer.tile_significant;
  std::vector<size_t> order(layer.tile_z.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::fabs(layer.tile_z[a]) > std::fabs(layer.tile_z[b]);
  });
  std::vector<uint8_t> mask(layer.tile_z.size(), 0);
  const size_t k = std::min(order.size(), size_t(std::max(0, layer.significant_tiles)));
  for (size_t i = 0; i < k; ++i)
    if (layer.tile_z[order[i]] != 0) mask[order[i]] = 1;
  return mask;
}

SignificanceMap significance_map(const LayerResult& layer, const RgbaImage& backdrop) {
  if (!tile_grid_ok(layer) ||
      layer.tiles_x != (backdrop.width + layer.tile_size - 1) / layer.tile_size ||
      layer.tiles_y != (backdrop.height + layer.tile_size - 1) / layer.tile_size)
    throw std::invalid_argument("significance_map: the tile grid does not cover the image");
  const std::vector<uint8_t> mask = significant_tile_mask(layer);
  SignificanceMap map{RgbaImage(backdrop.width, backdrop.height)};
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) map.z_scale = std::max(map.z_scale, double(std::fabs(layer.tile_z[i])));
  map.z_scale = std::max(map.z_scale, 1.0);
  const int ts = layer.tile_size;
  for (int y = 0; y < backdrop.height; ++y)
    for (int x = 0; x < backdrop.width; ++x) {
      const size_t tile = size_t(y / ts) * size_t(layer.tiles_x) + size_t(x / ts);
      const double shade = 0.15 + 0.5 * std::clamp(luma(backdrop, x, y), 0.0, 1.0);
      std::array<float, 3> c{float(shade), float(shade), float(shade)};
      if (mask[tile]) {
        const double z = layer.tile_z[tile];
        const double strength = std::clamp(std::fabs(z) / map.z_scale, 0.35, 1.0);
        const std::array<float, 3> ramp =
            ramp_colour(diverging_stops(), 0.5 + 0.5 * (z < 0 ? -strength : strength));
        const bool edge = x % ts == 0 || y % ts == 0;  // a thin line between flagged tiles
        for (size_t k = 0; k < 3; ++k)
          c[k] = float(0.15 * c[k] + 0.85 * ramp[k]) * (edge ? 0.7f : 1.f);
      }
      set_rgb(map.image, x, y, c);
    }
  return map;
}

}  // namespace vesper::regress

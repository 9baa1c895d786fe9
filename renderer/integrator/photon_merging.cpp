#include "renderer/integrator/photon_merging.h"

#include <cmath>

#include "renderer/math/constants.h"

namespace vesper {

float PhotonMerging::scale() const {
  const double r = double(map.radius());
  return float(1.0 / (double(subpaths) * (4.0 / 3.0) * kPi * r * r * r));
}

float photon_radius(double photons, double volume) {
  if (!(photons > 0.0) || !(volume > 0.0)) return 0.f;
  const double k = 32.0 * std::pow(photons / 1e6, 0.4);
  return float(std::cbrt(3.0 * k * volume / (4.0 * kPi * photons)));
}

}  // namespace vesper

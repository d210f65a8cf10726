// libFuzzer target: the contour pipeline fed arbitrary ranges (NaN, inf, negative, huge,
// denormal; 0 and more beams) and beam geometry, registered against a fixed scan and
// against itself. It must return a result, converged or not, never crash or hang.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/registration.h"

namespace {

contour_reg::LaserScan fixedScan() {
  contour_reg::LaserScan scan;  // a 4 m x 3 m room seen from inside, 360 beams
  scan.angle_min = -M_PI;
  scan.angle_increment = 2.0 * M_PI / 360.0;
  scan.range_max = 30.0;
  for (int n = 0; n < 360; ++n) {
    const double a = scan.bearing(static_cast<std::size_t>(n));
    const double c = std::abs(std::cos(a)), s = std::abs(std::sin(a));
    scan.ranges.push_back(static_cast<float>(std::min(c > 1e-9 ? 2.0 / c : 1e9, s > 1e-9 ? 1.5 / s : 1e9)));
  }
  return scan;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  contour_reg::LaserScan scan;
  double header[2] = {-2.0, 0.01};  // angle_min, angle_increment, from the first 16 bytes when present
  if (size >= sizeof header) {
    std::memcpy(header, data, sizeof header);
    data += sizeof header;
    size -= sizeof header;
  }
  scan.angle_min = header[0];
  scan.angle_increment = header[1];
  scan.range_max = 30.0;
  for (std::size_t k = 0; k + sizeof(float) <= size && scan.ranges.size() < 4096; k += sizeof(float)) {
    float r;
    std::memcpy(&r, data + k, sizeof r);
    scan.ranges.push_back(r);
  }
  const contour_reg::ContourParams params;
  const contour_reg::ContourFeatures features = contour_reg::extractContourFeatures(scan, params);
  static const contour_reg::ContourFeatures fixed = contour_reg::extractContourFeatures(fixedScan(), params);
  std::mt19937 rng(1);
  const contour_reg::RegistrationParams registration;
  (void)contour_reg::registerContours(features, fixed, registration, rng);
  (void)contour_reg::registerContours(features, features, registration, rng);
  return 0;
}

// The direction grid of Approx-Separation (penetration paper section 3,
// step 1, and Lemma 3.1).
//
// Guarantee wanted: every unit vector v is within angle theta of a grid
// direction u, with 1 / cos(theta) <= 1 + delta. Then the ray along u leaves M
// no farther than the plane of the facet closest to the origin, which it
// meets at distance PD / cos(angle(u, v)) <= (1 + delta) PD (Lemma 3.1; v is
// the direction of the minimum translation). The paper takes theta =
// sqrt(delta): cos(theta) >= 1 - theta^2 / 2 and 1 / (1 - x) <= 1 + 2x for
// x <= 1/2 give 1 / cos(theta) <= 1 + theta^2 = 1 + delta when delta <= 1.
// For delta > 1 that argument fails, so the angle is also capped by
// arccos(1 / (1 + delta)), where the bound holds with equality:
//     theta = coveringAngle(delta) = min(sqrt(delta), arccos(1 / (1 + delta))).
//
// Construction (latitude rings; the paper uses a plain (polar angle,
// azimuth) grid, which wastes directions near the poles):
//   - R = ceil(pi / (sqrt(2) theta)) rings at polar angles
//     phi_i = (i + 1/2) pi / R, i = 0..R-1: every polar angle is within
//     h = pi / (2R) <= theta / sqrt(2) of a ring's;
//   - on ring i, k_i >= 3 directions at azimuths 2 pi j / k_i: every azimuth
//     is within pi / k_i of one; k_i is the smallest count for which the
//     cell {|phi - phi_i| <= h, |psi - psi_j| <= pi / k_i} lies within
//     theta of its centre (phi_i, psi_j).
// Why checking the cell's corners suffices: with c = cos(dpsi),
//     cos(angle) = cos(phi) cos(phi_i) + sin(phi) sin(phi_i) c
// decreases in |dpsi| (sin >= 0 on [0, pi]), so the worst azimuth is the
// largest; at that azimuth it is rho cos(phi - gamma) with
// gamma = atan2(c sin(phi_i), cos(phi_i)), which for c > 0 (k_i >= 3) lies
// between phi_i and pi / 2, so the trough gamma +- pi is outside the band
// [phi_i - h, phi_i + h] (a subset of [0, pi]); the smallest cosine over the
// band is then at one of its ends. Counting: about 2 pi / theta^2 directions
// (square cells of half-diagonal theta), half of a cube map's 12 / theta^2.
// tests/lib/test_penetration_grid.cpp checks the covering angle by sampling.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "constants.h"
#include "mddual/defaults.h"
#include "mddual/error.h"
#include "penetration_internal.h"

namespace mddual {
namespace {

/// Largest angle between the centre (phi, 0) of a cell and its corners
/// (phi +- half_polar, half_azimuth).
double cornerAngle(double phi, double half_polar, double half_azimuth) {
  double worst = 0.0;
  for (double corner : {phi - half_polar, phi + half_polar}) {
    const double c = std::cos(corner) * std::cos(phi) + std::sin(corner) * std::sin(phi) * std::cos(half_azimuth);
    worst = std::max(worst, std::acos(std::clamp(c, -1.0, 1.0)));
  }
  return worst;
}

}  // namespace

double coveringAngle(double delta) {
  detail::checkDelta(delta, "coveringAngle");
  return std::min(std::sqrt(delta), std::acos(1.0 / (1.0 + delta)));
}

std::vector<Eigen::Vector3d> directionGrid(double delta) {
  const double theta = coveringAngle(delta);
  const int rings = static_cast<int>(std::ceil(kPi / (std::sqrt(2.0) * theta)));
  const double half_polar = 0.5 * kPi / rings;
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < rings; ++i) {
    const double phi = (i + 0.5) * 2.0 * half_polar;
    auto covers = [&](int k) { return cornerAngle(phi, half_polar, kPi / k) <= theta; };
    // Smallest k >= 3 that covers: double, then bisect (coverage is monotone in k).
    int hi = 3;
    while (!covers(hi)) hi *= 2;
    int lo = hi / 2;  // does not cover (or is below 3)
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      if (mid >= 3 && covers(mid)) {
        hi = mid;
      } else {
        lo = mid;
      }
    }
    const int k = hi;
    // Serpentine order: consecutive directions are neighbours (warm starts).
    for (int jj = 0; jj < k; ++jj) {
      const int j = i % 2 == 0 ? jj : k - 1 - jj;
      const double psi = 2.0 * kPi * j / k;
      out.emplace_back(std::sin(phi) * std::cos(psi), std::sin(phi) * std::sin(psi), std::cos(phi));
    }
  }
  return out;
}

namespace detail {

void checkDelta(double delta, const char* what) {
  if (!(delta >= defaults::kMinPdDelta && delta <= defaults::kMaxPdDelta)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << what << ": delta " << delta << " must be a number in [" << defaults::kMinPdDelta << ", "
        << defaults::kMaxPdDelta << "]";
    throw InvalidInputError(msg.str());
  }
}

}  // namespace detail
}  // namespace mddual

// Dense references of an edge's first contact, for the tests and the
// soundness suite (benchmarks/soundness): plain sampling, no certificate.
// Not part of the installed package (planners/CMakeLists.txt leaves it out).
//
//   - denseFirstContact(gap, speed, min_step): adaptive steps over t in
//     [0, 1]. gap(t) is a lower bound of the distance between the moving
//     bodies at t (<= 0: a contact, touching included), and `speed` bounds
//     how fast that distance can shrink per unit of t; the next sample is
//     gap / speed later (at least min_step), so no contact lies between two
//     samples unless it is within min_step of the later one.
//   - denseFirstContact(scene, q0, q1, steps): an arm edge q0 + t (q1 - q0)
//     at steps + 1 evenly spaced states, each checked by ArmScene::collides.
// Both return the first colliding sample's t, or +infinity when none is.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "mddual/planning/arm_scene.h"

namespace mddual::planning {

template <class GapFn>
double denseFirstContact(const GapFn& gap, double speed, double min_step) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double t = 0.0;
  for (;;) {
    const double g = gap(t);
    if (g <= 0.0) return t;
    if (t >= 1.0) return kInf;
    const double advance = speed > 0.0 ? g / speed : kInf;
    t = std::min(1.0, t + std::max(advance, min_step));
  }
}

inline double denseFirstContact(const ArmScene& scene, const std::vector<double>& q0, const std::vector<double>& q1,
                                int steps) {
  std::vector<double> q(q0.size());
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    for (std::size_t v = 0; v < q.size(); ++v) q[v] = q0[v] + t * (q1[v] - q0[v]);
    if (scene.collides(q.data())) return t;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace mddual::planning

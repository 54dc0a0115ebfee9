// Point sets that only the tests use (generators.h has those the benchmarks,
// the CLI demo and the Python module share): integer lattices, with many
// coplanar and collinear points, and the regular tetrahedron.
#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "mddual/generators.h"

namespace mddual::testing {

/// Integer lattice points {0..nx} x {0..ny} x {0..nz}, scaled by `spacing`.
inline generators::Points lattice(int nx, int ny, int nz, double spacing) {
  generators::Points p;
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j)
      for (int k = 0; k <= nz; ++k) p.emplace_back(spacing * i, spacing * j, spacing * k);
  return p;
}

/// Regular tetrahedron with edge length `edge`, centred at the origin.
inline generators::Points regularTetrahedron(double edge) {
  const double s = edge / (2.0 * std::sqrt(2.0));
  return {Eigen::Vector3d(s, s, s), Eigen::Vector3d(s, -s, -s), Eigen::Vector3d(-s, s, -s), Eigen::Vector3d(-s, -s, s)};
}

}  // namespace mddual::testing

// Optional interoperability with FCL (the Flexible Collision Library): a
// ConvexPolytope as an fcl::Convex<double>, the model every FCL comparison
// of this project uses (the planning layer's FCL baselines, the core's
// benchmarks against FCL's casts, the tests against FCL's distance).
//
// Header-only, and the only core header that includes FCL: include it where
// you link FCL, 0.7 or later (the constructor with throw_if_invalid). The
// core library itself does not need FCL.
#pragma once

#include <fcl/geometry/shape/convex.h>

#include <memory>
#include <vector>

#include "mddual/polytope.h"

namespace mddual {

/// p as an fcl::Convex<double> in p's body frame: its vertices, and its faces
/// from faceVertices() (counter-clockwise seen from outside), with the local
/// AABB computed. FCL validates the face mesh as closed unless p is flat (a
/// polygon: two opposite faces), whose support function still works.
inline std::shared_ptr<fcl::Convex<double>> toFclConvex(const ConvexPolytope& p) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3<double>>>(p.vertices().begin(), p.vertices().end());
  auto faces = std::make_shared<std::vector<int>>();
  for (int f = 0; f < p.numFaces(); ++f) {
    const IndexRange loop = p.faceVertices(f);
    faces->push_back(loop.size());
    faces->insert(faces->end(), loop.begin(), loop.end());
  }
  auto convex = std::make_shared<fcl::Convex<double>>(vertices, p.numFaces(), faces, /*throw_if_invalid=*/!p.isFlat());
  convex->computeLocalAABB();
  return convex;
}

}  // namespace mddual

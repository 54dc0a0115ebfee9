// A downstream project using the installed package: two unit cubes, B three
// units along -x, moving along +x, touch after 2 units.
#include <mddual/mddual.h>

#include <cmath>
#include <cstdio>

int main() {
  const mddual::ConvexPolytope cube = mddual::ConvexPolytope::fromPoints(mddual::generators::box({0.5, 0.5, 0.5}));
  mddual::DirectionalInput input;
  input.a = &cube;
  input.b = &cube;
  input.X_WB.translation() = Eigen::Vector3d(-3.0, 0.0, 0.0);
  input.s_W = Eigen::Vector3d(1.0, 0.0, 0.0);
  const mddual::MddResult r = mddual::mdd(input);
  std::printf("consumer: status %s, mdd %.17g\n", mddual::toString(r.status), r.distance);
  return r.status == mddual::ContactStatus::kSeparated && std::abs(r.distance - 2.0) < 1e-12 ? 0 : 1;
}

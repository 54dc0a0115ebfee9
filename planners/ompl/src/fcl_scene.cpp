#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>
#include <algorithm>
#include <cmath>
#include <vector>

#include "constants.h"
#include "mddual/error.h"
#include "mddual/fcl_interop.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/per_thread.h"

namespace mddual::planning {
namespace detail {

/// A collision object whose AABB the caller sets: the broad-phase query for a
/// swept volume. In a named namespace: FclScene::Impl (a class with linkage)
/// holds one.
class BoxQuery : public fcl::CollisionObject<double> {
 public:
  using fcl::CollisionObject<double>::CollisionObject;
  void setAabb(const fcl::AABB<double>& box) { aabb = box; }
};

}  // namespace detail
namespace {

using Geometry = fcl::CollisionGeometry<double>;
using Object = fcl::CollisionObject<double>;
using detail::BoxQuery;
using detail::kInf;

/// The triangle soup of the kTriangle pieces (nullptr when there are none).
std::shared_ptr<Geometry> triangleSoup(const std::vector<scene::Piece>& pieces) {
  std::vector<fcl::Vector3<double>> points;
  std::vector<fcl::Triangle> triangles;
  for (const scene::Piece& piece : pieces) {
    if (piece.kind != scene::PieceKind::kTriangle) continue;
    const ConvexPolytope& p = piece.polytope;
    const IndexRange loop = p.faceVertices(0);  // a flat polygon: its vertex loop
    const auto base = points.size();
    for (int v : loop) points.push_back(p.vertex(v));
    for (int k = 1; k + 1 < loop.size(); ++k) {
      triangles.emplace_back(base, base + static_cast<std::size_t>(k), base + static_cast<std::size_t>(k) + 1);
    }
  }
  if (triangles.empty()) return nullptr;
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

/// One geometry per convex piece, then the soup of the triangles.
std::vector<std::shared_ptr<Geometry>> geometries(const std::vector<scene::Piece>& pieces) {
  std::vector<std::shared_ptr<Geometry>> out;
  for (const scene::Piece& piece : pieces) {
    if (piece.kind == scene::PieceKind::kConvex) out.push_back(toFclConvex(piece.polytope));
  }
  if (auto soup = triangleSoup(pieces)) out.push_back(soup);
  return out;
}

/// A BVH model rebuilt from `g`'s triangles with its own fitter and splitter
/// (FCL's mesh-mesh conservative advancement refits copies of the models that
/// share those with the original: not thread-safe); other geometries as is.
std::shared_ptr<Geometry> privateCopy(const std::shared_ptr<Geometry>& g) {
  const auto* bvh = dynamic_cast<const fcl::BVHModel<fcl::OBBRSS<double>>*>(g.get());
  if (!bvh) return g;
  std::vector<fcl::Vector3<double>> points(bvh->vertices, bvh->vertices + bvh->num_vertices);
  std::vector<fcl::Triangle> triangles(bvh->tri_indices, bvh->tri_indices + bvh->num_tris);
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  model->beginModel(bvh->num_tris, bvh->num_vertices);
  model->addSubModel(points, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

bool isBvh(const Geometry* g) {
  return dynamic_cast<const fcl::BVHModel<fcl::OBBRSS<double>>*>(g) != nullptr;
}

/// `g` as a BVH triangle model when it is an fcl::Convex (its faces fanned
/// into triangles), else `g`. FCL 0.7's conservative advancement between a
/// convex shape and a BVH model crashes (shape first: unbounded recursion in
/// distanceRecurse) or misses even a thick obstacle (BVH first), so a mixed
/// pair is checked as two meshes, the pair kind FCL's advancement supports (it
/// still misses some thin walls there, as between convex shapes).
std::shared_ptr<Geometry> asMesh(const std::shared_ptr<Geometry>& g) {
  const auto* convex = dynamic_cast<const fcl::Convex<double>*>(g.get());
  if (!convex) return g;
  const std::vector<int>& faces = convex->getFaces();
  std::vector<fcl::Triangle> triangles;
  for (std::size_t i = 0; i < faces.size(); i += static_cast<std::size_t>(faces[i]) + 1) {
    for (int k = 1; k + 1 < faces[i]; ++k) {
      triangles.emplace_back(static_cast<std::size_t>(faces[i + 1]), static_cast<std::size_t>(faces[i + 1 + k]),
                             static_cast<std::size_t>(faces[i + 2 + k]));
    }
  }
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(convex->getVertices().size()));
  model->addSubModel(convex->getVertices(), triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

fcl::AABB<double> toFcl(const Eigen::AlignedBox3d& b) {
  return fcl::AABB<double>(b.min(), b.max());
}

Eigen::AlignedBox3d toEigen(const fcl::AABB<double>& b) {
  return Eigen::AlignedBox3d(b.min_, b.max_);
}

struct CollideData {
  fcl::CollisionRequest<double> request;
  bool hit = false;
  int queries = 0;
};

bool collideCallback(Object* o1, Object* o2, void* cdata) {
  auto* data = static_cast<CollideData*>(cdata);
  fcl::CollisionResult<double> result;
  ++data->queries;
  if (fcl::collide(o1, o2, data->request, result) > 0) data->hit = true;
  return data->hit;
}

struct DistanceData {
  fcl::DistanceRequest<double> request;
  double min_distance = kInf;
  /// Skip triangle-mesh against triangle-mesh pairs: FCL computes their
  /// distance triangle by triangle without GJK, so the second solver's pass
  /// would repeat the first's answer (on a 3,000 x 40,000 triangle pair that
  /// was half of the time).
  bool skip_mesh_pairs = false;
};

bool distanceCallback(Object* o1, Object* o2, void* cdata, double& dist) {
  auto* data = static_cast<DistanceData*>(cdata);
  if (data->skip_mesh_pairs && o1->getObjectType() == fcl::OT_BVH && o2->getObjectType() == fcl::OT_BVH) {
    dist = data->min_distance;
    return false;
  }
  fcl::DistanceResult<double> result;
  fcl::distance(o1, o2, data->request, result);
  data->min_distance = std::min(data->min_distance, result.min_distance);
  dist = data->min_distance;
  return data->min_distance <= 0.0;
}

struct CandidateData {
  const Object* query = nullptr;
  std::vector<const Object*> found;
};

bool candidateCallback(Object* o1, Object* o2, void* cdata) {
  auto* data = static_cast<CandidateData*>(cdata);
  data->found.push_back(o1 == data->query ? o2 : o1);
  return false;
}

}  // namespace

const char* toString(FclCcdSolver solver) {
  return solver == FclCcdSolver::kNaive ? "naive" : "conservative_advancement";
}

struct FclScene::Impl {
  /// Per thread: the robot's collision objects (their poses change per query),
  /// a box query object for swept volumes, and private copies of the triangle
  /// soups for continuous collision (see privateCopy).
  struct Local {
    std::vector<std::unique_ptr<Object>> robot;
    std::unique_ptr<detail::BoxQuery> query;
    std::vector<std::shared_ptr<Geometry>> robot_ccd;
    std::vector<std::shared_ptr<Geometry>> world_ccd;
    /// The same as meshes (asMesh), when the scene mixes shapes and meshes.
    std::vector<std::shared_ptr<Geometry>> robot_ccd_mesh;
    std::vector<std::shared_ptr<Geometry>> world_ccd_mesh;
  };

  std::shared_ptr<const scene::RigidBody> robot;
  std::shared_ptr<const scene::World> world;
  std::vector<std::shared_ptr<Geometry>> robot_geometry;
  /// Largest distance of a point of each robot geometry from the body origin.
  std::vector<double> robot_radius;
  std::vector<std::shared_ptr<Geometry>> world_geometry;
  std::vector<std::unique_ptr<Object>> world_objects;
  fcl::DynamicAABBTreeCollisionManager<double> manager;
  std::shared_ptr<Geometry> query_box = std::make_shared<fcl::Box<double>>(1.0, 1.0, 1.0);
  std::mutex make_mutex;
  PerThread<Local> local_cache;

  std::shared_ptr<Local> local() {
    return local_cache.local([this] {
      std::lock_guard<std::mutex> lock(make_mutex);  // CollisionObject() writes to the shared geometry
      auto l = std::make_shared<Local>();
      for (const auto& g : robot_geometry) l->robot.push_back(std::make_unique<Object>(g));
      l->query = std::make_unique<BoxQuery>(query_box);
      for (const auto& g : robot_geometry) l->robot_ccd.push_back(privateCopy(g));
      for (const auto& g : world_geometry) l->world_ccd.push_back(privateCopy(g));
      const auto bvhs = [](const std::vector<std::shared_ptr<Geometry>>& gs) {
        return std::count_if(gs.begin(), gs.end(), [](const auto& g) { return isBvh(g.get()); });
      };
      const auto robot_bvhs = bvhs(l->robot_ccd);
      const auto world_bvhs = bvhs(l->world_ccd);
      const bool mixed = (robot_bvhs > 0 && world_bvhs < static_cast<long>(l->world_ccd.size())) ||
                         (world_bvhs > 0 && robot_bvhs < static_cast<long>(l->robot_ccd.size()));
      if (mixed) {
        for (const auto& g : l->robot_ccd) l->robot_ccd_mesh.push_back(asMesh(g));
        for (const auto& g : l->world_ccd) l->world_ccd_mesh.push_back(asMesh(g));
      }
      return l;
    });
  }
};

FclScene::FclScene(std::shared_ptr<const scene::RigidBody> robot, std::shared_ptr<const scene::World> world)
    : impl_(std::make_unique<Impl>()) {
  if (!robot) throw InvalidInputError("FclScene: the robot is null");
  if (!world) throw InvalidInputError("FclScene: the world is null");
  impl_->robot = std::move(robot);
  impl_->world = std::move(world);
  impl_->robot_geometry = geometries(impl_->robot->pieces());
  for (const auto& g : impl_->robot_geometry) {
    // Radius about the body origin: the local AABB's farthest corner bounds it.
    const fcl::AABB<double>& b = g->aabb_local;
    double r = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c((corner & 1) ? b.max_.x() : b.min_.x(), (corner & 2) ? b.max_.y() : b.min_.y(),
                              (corner & 4) ? b.max_.z() : b.min_.z());
      r = std::max(r, c.norm());
    }
    impl_->robot_radius.push_back(r);
  }
  impl_->world_geometry = geometries(impl_->world->pieces());
  std::vector<Object*> registered;
  for (const auto& g : impl_->world_geometry) {
    impl_->world_objects.push_back(std::make_unique<Object>(g));
    impl_->world_objects.back()->setUserData(reinterpret_cast<void*>(impl_->world_objects.size() - 1));
    impl_->world_objects.back()->computeAABB();
    registered.push_back(impl_->world_objects.back().get());
  }
  impl_->manager.registerObjects(registered);
  impl_->manager.setup();
}

FclScene::~FclScene() = default;

int FclScene::robotObjectCount() const {
  return static_cast<int>(impl_->robot_geometry.size());
}
int FclScene::worldObjectCount() const {
  return static_cast<int>(impl_->world_objects.size());
}

bool FclScene::collides(const Eigen::Isometry3d& X_WR, int* pair_queries) const {
  const std::shared_ptr<Impl::Local> local = impl_->local();
  CollideData data;
  for (const auto& object : local->robot) {
    object->setTransform(X_WR);
    object->computeAABB();
    impl_->manager.collide(object.get(), &data, collideCallback);
    if (data.hit) break;
  }
  if (pair_queries) *pair_queries += data.queries;
  return data.hit;
}

double FclScene::distance(const Eigen::Isometry3d& X_WR) const {
  const std::shared_ptr<Impl::Local> local = impl_->local();
  double best = kInf;
  for (const fcl::GJKSolverType solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    DistanceData data;
    data.request.gjk_solver_type = solver;
    data.skip_mesh_pairs = solver != fcl::GST_LIBCCD;
    for (const auto& object : local->robot) {
      object->setTransform(X_WR);
      object->computeAABB();
      impl_->manager.distance(object.get(), &data, distanceCallback);
      if (data.min_distance <= 0.0) break;
    }
    best = std::min(best, data.min_distance);
  }
  return best;
}

FclScene::Continuous FclScene::continuousCollide(const Eigen::Isometry3d& X_start, const Eigen::Isometry3d& X_end,
                                                 bool screw, const FclCcdOptions& options) const {
  const std::shared_ptr<Impl::Local> local = impl_->local();
  fcl::ContinuousCollisionRequest<double> request;
  request.num_max_iterations = static_cast<std::size_t>(options.num_max_iterations);
  request.toc_err = options.toc_err;
  request.ccd_motion_type = screw ? fcl::CCDM_SCREW : fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type =
      options.solver == FclCcdSolver::kNaive ? fcl::CCDC_NAIVE : fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  // A translation keeps the start orientation (FCL's TranslationMotion does).
  Eigen::Isometry3d X_to = X_end;
  if (!screw) X_to.linear() = X_start.linear();
  // Screw motion: each point moves on a helix whose projection is a circular
  // arc of angle a; the arc leaves its chord (length <= |dp| + 2 r) by at most
  // chord / 2 * tan(a / 4): pad the end boxes by that.
  double tan_quarter = 0.0;
  double half_dp = 0.0;
  if (screw) {
    tan_quarter = std::tan(Eigen::AngleAxisd(X_start.linear().transpose() * X_end.linear()).angle() / 4.0);
    half_dp = 0.5 * (X_end.translation() - X_start.translation()).norm();
  }
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  Continuous out;
  for (std::size_t k = 0; k < local->robot.size(); ++k) {
    Object& object = *local->robot[k];
    object.setTransform(X_start);
    object.computeAABB();
    Eigen::AlignedBox3d box = toEigen(object.getAABB());
    object.setTransform(X_to);
    object.computeAABB();
    box.extend(toEigen(object.getAABB()));
    if (screw) {
      const double r = tan_quarter * (half_dp + impl_->robot_radius[k]);
      box.min().array() -= r;
      box.max().array() += r;
    }
    local->query->setAabb(toFcl(box));
    CandidateData candidates;
    candidates.query = local->query.get();
    impl_->manager.collide(local->query.get(), &candidates, candidateCallback);
    for (const Object* w : candidates.found) {
      fcl::ContinuousCollisionResult<double> result;
      ++out.pair_queries;
      const auto index = reinterpret_cast<std::size_t>(w->getUserData());
      const Geometry* robot_g = local->robot_ccd[k].get();
      const Geometry* world_g = local->world_ccd[index].get();
      if (request.ccd_solver_type == fcl::CCDC_CONSERVATIVE_ADVANCEMENT && isBvh(robot_g) != isBvh(world_g)) {
        robot_g = local->robot_ccd_mesh[k].get();  // see asMesh
        world_g = local->world_ccd_mesh[index].get();
      }
      fcl::continuousCollide(robot_g, X_start, X_to, world_g, identity, identity, request, result);
      if (result.is_collide && result.time_of_contact < out.time) {
        out.collides = true;
        out.time = std::max(0.0, result.time_of_contact);
      }
    }
  }
  return out;
}

}  // namespace mddual::planning

// ArmScene (arm_scene.h): state checks, clearance and the certified motion
// check of joint-space edges. The argument: docs/design/arms.md.
#include "mddual/planning/arm_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "constants.h"
#include "mddual/distance.h"
#include "mddual/error.h"
#include "mddual/query.h"

namespace mddual::planning {
namespace {

using detail::kInf;
/// Relative growth of a pair's motion bound and of its free window: covers
/// the round-off of forward kinematics and of the bound's own sums.
constexpr double kRateSlackRel = 1e-9;
/// Shortest interval (fraction of the edge) the recursion splits.
constexpr double kMinInterval = 1e-12;
/// GJK on a leaf pair of pairWindow stops once its lower bound is within
/// this fraction of its upper bound: the window shrinks by at most that
/// much, and GJK runs fewer iterations. On arm7 (mddual_bench_arm_edges,
/// bookshelf_thin and cage) 0.25 took 10% fewer instructions per motion
/// check than GJK's full precision, 0.02 5%, 0.5 no fewer than 0.25.
constexpr double kWindowGapRel = 0.25;

std::vector<const ConvexPolytope*> polytopesOf(const std::vector<scene::Piece>& pieces) {
  std::vector<const ConvexPolytope*> out;
  out.reserve(pieces.size());
  for (const scene::Piece& p : pieces) out.push_back(&p.polytope);
  return out;
}

/// Links of more pieces than this get cluster hulls, on two levels: first
/// the hulls of their two halves (split along the longest axis of the
/// pieces' centres), then hulls of at most this many pieces each. A hull
/// holds its pieces, so the bounds stay lower bounds; the finer levels are
/// searched only where a coarser one comes within the contact distance. On
/// arm7 (mddual_bench_arm_edges, bookshelf_thin and cage) this took a third
/// fewer instructions per motion check than clusters of 24 alone, and a tenth
/// fewer than one hull per link above the clusters.
constexpr int kClusterPieces = 24;

/// Largest cluster of `level` for a link of n pieces.
int clusterSize(int level, int n) {
  return level == 0 ? (n + 1) / 2 : kClusterPieces;
}

/// Configurations this thread recently found free (a state check, or the
/// ends of an edge certified free), per scene. checkEdge skips its end-state
/// check for them: the goal trees of RRT-Connect and BKPIECE check edges that
/// end at a tree state, found free before. A hint only: the search covers the
/// whole edge whatever the memo says, so a wrong entry costs a state check
/// and never a miss. Direct-mapped on the exact values of the variables.
class FreeMemo {
 public:
  bool contains(std::uint64_t scene, const double* q, int n) const {
    const Slot& s = slots_[index(q, n)];
    return s.scene == scene && std::equal(s.q.begin(), s.q.end(), q, q + n);
  }
  void insert(std::uint64_t scene, const double* q, int n) {
    Slot& s = slots_[index(q, n)];
    s.scene = scene;
    s.q.assign(q, q + n);
  }

 private:
  static constexpr std::size_t kSlots = 1024;
  struct Slot {
    std::uint64_t scene = 0;  ///< 0: empty (scene serials start at 1)
    std::vector<double> q;
  };
  static std::size_t index(const double* q, int n) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int v = 0; v < n; ++v) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &q[v], sizeof bits);
      h = (h ^ bits) * 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
    }
    return static_cast<std::size_t>(h % kSlots);
  }
  std::vector<Slot> slots_ = std::vector<Slot>(kSlots);
};

FreeMemo& freeMemo() {
  thread_local FreeMemo memo;
  return memo;
}

std::atomic<std::uint64_t> g_next_serial{1};

}  // namespace

/// What one checkEdge call carries through the recursion. Each thread keeps
/// one and reuses its buffers from call to call (reset()): allocations were
/// a tenth of a motion check's instructions (mddual_bench_arm_edges, cage).
struct ArmScene::EdgeWork {
  /// The robot at one time of the edge: link poses and joint axes (world
  /// frame: a point of each axis and its direction).
  struct Probe {
    double t = -1.0;
    std::vector<Eigen::Isometry3d> X_WL;
    std::vector<Eigen::Vector3d> o_W, u_W;
  };
  /// Probes kept: every pair's search starts at t = 1/2 (slot 0, kept for the
  /// whole edge); the others go round the remaining slots. Probe times are
  /// snapped to a grid (probeTime()), so pairs share them.
  static constexpr std::size_t kProbes = 24;

  const double* q0 = nullptr;
  std::vector<double> dq;
  EdgeQuery query = EdgeQuery::kValidity;
  std::vector<double> q;
  ArmEdgeResult* result = nullptr;
  /// Search only below this fraction (the best first contact so far).
  double limit = kInf;
  /// kLastValid: how far below `limit` a pair may stop (checkEdge's
  /// fraction_tolerance).
  double tolerance = 0.0;
  std::vector<Probe> probes = std::vector<Probe>(kProbes);
  std::size_t next = 1;
  /// The current probe (poseAt()).
  const Probe* at = nullptr;
  /// pairWindow's scratch per side: each node's ball rate, valid when its
  /// stamp is the side's current one (one stamp per pairWindow call, so no
  /// call clears the buffer). And GJK's warm starts per (pair, leaf, leaf).
  struct SideScratch {
    std::vector<std::pair<std::uint32_t, double>> rates;
    std::uint32_t stamp = 0;
    /// Ready for a tree of n nodes; no entry valid.
    void start(int n) {
      if (rates.size() < static_cast<std::size_t>(n)) rates.resize(static_cast<std::size_t>(n), {0, 0.0});
      if (++stamp == 0) {  // wrapped: forget every entry
        for (auto& e : rates) e.first = 0;
        stamp = 1;
      }
    }
  };
  SideScratch sides[2];
  /// Per pair, whether no joint between its sides moves on this edge
  /// (-1: not known yet), and whether the validity search cleared it on the
  /// whole edge.
  std::vector<signed char> still, cleared;
  std::vector<std::pair<int, int>> stack;

  /// GJK's warm starts, per (pair, leaf, leaf) key: an open-addressing table
  /// whose entries of earlier calls are stale by their stamp. When it is
  /// half full, new keys go without a warm start.
  struct WarmSlot {
    std::uint64_t key = 0;
    std::uint32_t stamp = 0;
    DistanceWarmStart warm;
  };
  static constexpr std::size_t kWarmSlots = 1024;
  std::vector<WarmSlot> warm = std::vector<WarmSlot>(kWarmSlots);
  std::uint32_t stamp = 0;
  std::size_t warm_used = 0;
  DistanceWarmStart* warmStart(std::uint64_t key) {
    std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 54) & (kWarmSlots - 1);
    for (;; i = (i + 1) & (kWarmSlots - 1)) {
      WarmSlot& s = warm[i];
      if (s.stamp == stamp && s.key == key) return &s.warm;
      if (s.stamp != stamp) {
        if (2 * warm_used >= kWarmSlots) return nullptr;
        ++warm_used;
        s = {key, stamp, DistanceWarmStart()};
        return &s.warm;
      }
    }
  }

  /// Ready for a new edge from q0 with changes q1 - q0.
  void reset(const double* q0_in, const double* q1, int nv, int pairs, EdgeQuery query_in, ArmEdgeResult* result_in) {
    q0 = q0_in;
    dq.resize(static_cast<std::size_t>(nv));
    for (int v = 0; v < nv; ++v) dq[static_cast<std::size_t>(v)] = q1[v] - q0[v];
    q.resize(static_cast<std::size_t>(nv));
    query = query_in;
    result = result_in;
    limit = kInf;
    tolerance = 0.0;
    for (Probe& p : probes) p.t = -1.0;
    next = 1;
    at = nullptr;
    if (++stamp == 0) {  // the stamps wrapped: forget every entry
      for (WarmSlot& s : warm) s.stamp = 0;
      stamp = 1;
    }
    warm_used = 0;
    still.assign(static_cast<std::size_t>(pairs), -1);
    cleared.assign(static_cast<std::size_t>(pairs), 0);
  }

  /// Where the search of [a, b] probes: its midpoint moved to the nearest
  /// multiple of the largest power of two at most (b - a) / 2 (so at most a
  /// quarter of the interval from the middle), so that pairs searching
  /// similar intervals probe at the same times and share one forward
  /// kinematics. On arm7's motion checks (mddual_bench_arm_edges,
  /// bookshelf_thin and cage) this took 4% fewer instructions than
  /// (b - a) / 4, which took 5% fewer than the midpoints; (b - a) / 1 took
  /// more than (b - a) / 4.
  static double probeTime(double a, double b) {
    const double tm = 0.5 * (a + b);
    int e = 0;
    std::frexp((b - a) / 2.0, &e);  // (b - a) / 2 in [2^(e-1), 2^e)
    const double h = std::ldexp(1.0, e - 1);
    const double t = std::round(tm / h) * h;
    return t > a && t < b ? t : tm;
  }

  /// How far (world units per unit |t - probe|) a point of a ball (centre
  /// c_W, radius r) moved by `movers` can get from where it is at the probe
  /// `at`: per joint, its speed times the ball's distance from the joint's
  /// axis at the probe, never more than the joint's reach. Turning the
  /// joints one after the other from the root, each turn moves the point by
  /// at most its angle times the point's distance from that axis at the
  /// probe, whatever the later joints do (docs/design/arms.md).
  double ballRate(const std::vector<Mover>& movers, const Eigen::Vector3d& c_W, double r) const {
    double rho = 0.0;
    for (const Mover& mv : movers) {
      const double speed = std::abs(dq[static_cast<std::size_t>(mv.variable)]) * mv.multiplier;
      if (speed == 0.0) continue;
      double arm = 1.0;  // prismatic: the ball moves at the joint's speed
      if (!mv.prismatic) {
        const std::size_t j = static_cast<std::size_t>(mv.joint);
        const Eigen::Vector3d v = c_W - at->o_W[j];
        arm = std::min(mv.reach, (v - v.dot(at->u_W[j]) * at->u_W[j]).norm() + r);
      }
      rho += speed * arm;
    }
    return rho * (1.0 + kRateSlackRel);
  }

  /// Makes `at` the robot at time t, computed or kept from before.
  void poseAt(const ArmScene& scene, double t) {
    for (const Probe& p : probes) {
      if (p.t == t) {
        at = &p;
        return;
      }
    }
    Probe& p = probes[t == 0.5 ? 0 : next];
    if (t != 0.5) next = next + 1 < kProbes ? next + 1 : 1;
    p.t = t;
    for (std::size_t v = 0; v < dq.size(); ++v) q[v] = q0[v] + t * dq[v];
    scene.linkPoses(q.data(), &p.X_WL);
    const scene::RobotModel& m = scene.model();
    p.o_W.resize(m.joints().size());
    p.u_W.resize(p.o_W.size());
    for (int j = 0; j < static_cast<int>(m.joints().size()); ++j) {
      const scene::Joint& joint = m.joint(j);
      if (!joint.moves()) continue;
      const Eigen::Isometry3d& X_WC = p.X_WL[static_cast<std::size_t>(joint.child_link)];
      p.o_W[static_cast<std::size_t>(j)] = X_WC.translation();
      p.u_W[static_cast<std::size_t>(j)] = X_WC.linear() * joint.axis_J;
    }
    at = &p;
  }
};

ArmScene::ArmScene(std::shared_ptr<const scene::RobotModel> model, std::shared_ptr<const scene::World> world,
                   scene::AllowedCollisions filter, const Eigen::Isometry3d& X_WB, const ArmSceneOptions& options)
    : model_(std::move(model)),
      world_(std::move(world)),
      filter_(std::move(filter)),
      X_WB_(X_WB),
      options_(options),
      serial_(g_next_serial.fetch_add(1, std::memory_order_relaxed)) {
  if (!model_) throw InvalidInputError("ArmScene: null robot model");
  if (!world_) throw InvalidInputError("ArmScene: null world");
  if (filter_.numLinks() != model_->numLinks()) {
    throw InvalidInputError("ArmScene: the self-collision filter has " + std::to_string(filter_.numLinks()) +
                            " links, the robot " + std::to_string(model_->numLinks()));
  }
  if (!X_WB_.matrix().allFinite()) throw InvalidInputError("ArmScene: the base pose X_WB is not finite");
  base_is_identity_ = X_WB_.matrix().isIdentity(0.0);
  if (!(options_.contact_distance > 0.0) || !std::isfinite(options_.contact_distance)) {
    throw InvalidInputError("ArmScene: contact_distance must be a finite number > 0");
  }
  if (options_.max_depth < 1 || options_.max_depth > 200) {
    throw InvalidInputError("ArmScene: max_depth must be in [1, 200]");
  }
  world_polytopes_ = polytopesOf(world_->pieces());
  world_tree_ = Bvh::fromPolytopes(world_polytopes_);
  const int nl = model_->numLinks();
  link_trees_.resize(static_cast<std::size_t>(nl));
  link_polytopes_.resize(static_cast<std::size_t>(nl));
  for (std::vector<Clusters>& level : clusters_) level.resize(static_cast<std::size_t>(nl));
  double reach = 0.0;
  for (int k = 0; k < nl; ++k) {
    const scene::Link& link = model_->link(k);
    const std::size_t ku = static_cast<std::size_t>(k);
    link_polytopes_[ku] = polytopesOf(link.pieces);
    if (!link.pieces.empty()) link_trees_[ku] = Bvh::fromPolytopes(link_polytopes_[ku]);
    const int n = static_cast<int>(link.pieces.size());
    for (int level = 0; level < kPieceLevel && n > kClusterPieces; ++level) {
      Clusters& c = clusters_[level][ku];
      c.hulls = scene::clusterHulls(link.pieces, clusterSize(level, n));
      if (level > 0 && c.hulls.size() == clusters_[level - 1][ku].hulls.size()) {
        c.hulls.clear();  // the same clusters as the level above
        continue;
      }
      for (const ConvexPolytope& h : c.hulls) c.polytopes.push_back(&h);
      c.tree = Bvh::fromPolytopes(c.polytopes);
    }
    if (link.parent_joint >= 0) reach = std::max(reach, model_->reach(model_->jointPath(k).front(), k));
  }
  scale_ = std::max({1.0, reach, world_->box().isEmpty() ? 0.0 : world_->box().diagonal().norm()});
  search_distance_ = options_.contact_distance + kRateSlackRel * scale_ * 1e-3;

  const int nv = model_->numVariables();
  // Per variable, how far the joints it drives on `joints` can move link k.
  auto addReach = [&](Pair* pair, const std::vector<int>& joints, int k) {
    std::vector<Mover>& movers = k == pair->link ? pair->link_movers : pair->other_movers;
    for (int j : joints) {
      const scene::Joint& joint = model_->joint(j);
      if (!joint.moves()) continue;
      const bool prismatic = joint.type == scene::JointType::kPrismatic;
      const double r = prismatic ? 1.0 : model_->reach(j, k);
      pair->reach[static_cast<std::size_t>(joint.variable)] += std::abs(joint.multiplier) * r;
      movers.push_back({j, joint.variable, std::abs(joint.multiplier), prismatic, r});
    }
  };
  if (!world_->pieces().empty()) {
    // Distal links first (links are stored parents first): they meet the
    // world most, and a validity check stops at its first contact.
    for (int k = nl - 1; k >= 0; --k) {
      if (model_->link(k).pieces.empty() || filter_.allowedWithWorld(k)) continue;
      Pair pair;
      pair.link = k;
      pair.reach.assign(static_cast<std::size_t>(nv), 0.0);
      addReach(&pair, model_->jointPath(k), k);
      pairs_.push_back(std::move(pair));
    }
  }
  for (int k = 0; k < nl; ++k) {
    for (int l = k + 1; l < nl; ++l) {
      if (model_->link(k).pieces.empty() || model_->link(l).pieces.empty() || filter_.allowed(k, l)) continue;
      self_pairs_.emplace_back(k, l);
      // Only the joints below the common ancestor move k and l apart.
      const std::size_t common = model_->jointPath(model_->commonAncestor(k, l)).size();
      Pair pair;
      pair.link = k;
      pair.other = l;
      pair.reach.assign(static_cast<std::size_t>(nv), 0.0);
      const std::vector<int> path_k = model_->jointPath(k);
      const std::vector<int> path_l = model_->jointPath(l);
      addReach(&pair, std::vector<int>(path_k.begin() + static_cast<std::ptrdiff_t>(common), path_k.end()), k);
      addReach(&pair, std::vector<int>(path_l.begin() + static_cast<std::ptrdiff_t>(common), path_l.end()), l);
      pairs_.push_back(std::move(pair));
    }
  }
}

void ArmScene::linkPoses(const double* q, std::vector<Eigen::Isometry3d>* X_WL) const {
  model_->linkPoses(q, X_WL);
  if (base_is_identity_) return;
  for (Eigen::Isometry3d& X : *X_WL) X = X_WB_ * X;
}

double ArmScene::pairRate(int p, const double* dq) const {
  const Pair& pair = pairs_[static_cast<std::size_t>(p)];
  double rate = 0.0;
  for (std::size_t v = 0; v < pair.reach.size(); ++v) rate += std::abs(dq[v]) * pair.reach[v];
  return rate;
}

ArmScene::PairView ArmScene::view(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL) const {
  const std::size_t k = static_cast<std::size_t>(p.link);
  if (p.other < 0) return {&world_->pieces(), &model_->link(p.link).pieces, &world_tree_, &link_trees_[k], X_WL[k]};
  const std::size_t l = static_cast<std::size_t>(p.other);
  return {&model_->link(p.link).pieces, &model_->link(p.other).pieces, &link_trees_[k], &link_trees_[l],
          X_WL[k].inverse() * X_WL[l]};
}

double ArmScene::pairBound(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, double upper) const {
  const PairView v = view(p, X_WL);
  const auto search = [&](const Bvh& a_tree, const std::vector<const ConvexPolytope*>& a, const Bvh& b_tree,
                          const std::vector<const ConvexPolytope*>& b) {
    return nearestPair(
               a_tree, b_tree, v.X_AB,
               [&](int i, int j, double best) {
                 DistanceInput in;
                 in.a = a[static_cast<std::size_t>(i)];
                 in.b = b[static_cast<std::size_t>(j)];
                 in.X_WB = v.X_AB;
                 return separationLowerBound(in, nullptr, best);
               },
               upper)
        .value;
  };
  // Coarse to fine: a link of many pieces by its clusters' hulls (each holds
  // its pieces, so the bound stays a lower bound), enough unless the pair
  // comes within the contact distance; then the next level.
  const int side_a = p.other < 0 ? -1 : p.link;
  const int side_b = p.other < 0 ? p.link : p.other;
  double bound = 0.0;
  for (int level = 0; level <= kPieceLevel; ++level) {
    if (level > 0 && !refines(p, level)) continue;
    const Side a = side(side_a, level), b = side(side_b, level);
    bound = search(*a.tree, *a.polytopes, *b.tree, *b.polytopes);
    if (bound > options_.contact_distance) break;
  }
  return bound;
}

bool ArmScene::refines(const Pair& p, int level) const {
  for (const int link : {p.link, p.other}) {
    if (link >= 0 && side(link, level).tree != side(link, level - 1).tree) return true;
  }
  return false;
}

ArmScene::Side ArmScene::side(int link, int level) const {
  if (link < 0) return {&world_tree_, &world_polytopes_};
  const std::size_t k = static_cast<std::size_t>(link);
  for (int l = level; l < kPieceLevel; ++l) {
    const Clusters& c = clusters_[l][k];
    if (!c.hulls.empty()) return {&c.tree, &c.polytopes};
  }
  return {&link_trees_[k], &link_polytopes_[k]};
}

bool ArmScene::pairCollides(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, ArmContact* which) const {
  const PairView v = view(p, X_WL);
  bool hit = false;
  forEachOverlappingPair(*v.a_tree, *v.b_tree, v.X_AB, 0.0, [&](int i, int j) {
    IntersectInput in;
    in.a = &(*v.a)[static_cast<std::size_t>(i)].polytope;
    in.b = &(*v.b)[static_cast<std::size_t>(j)].polytope;
    in.X_WB = v.X_AB;
    if (!intersect(in).intersecting) return true;
    hit = true;
    if (which != nullptr) *which = {p.link, p.other < 0 ? i : -1, p.other};
    return false;
  });
  return hit;
}

double ArmScene::pairDistance(const Pair& p, const std::vector<Eigen::Isometry3d>& X_WL, ArmContact* which) const {
  const PairView v = view(p, X_WL);
  const NearestHit hit = nearestPair(*v.a_tree, *v.b_tree, v.X_AB, [&](int i, int j, double /*best*/) {
    DistanceInput in;
    in.a = &(*v.a)[static_cast<std::size_t>(i)].polytope;
    in.b = &(*v.b)[static_cast<std::size_t>(j)].polytope;
    in.X_WB = v.X_AB;
    return distance(in).distance;
  });
  if (which != nullptr && hit.piece_a >= 0) *which = {p.link, p.other < 0 ? hit.piece_a : -1, p.other};
  return hit.value;
}

bool ArmScene::collides(const double* q, ArmContact* which) const {
  std::vector<Eigen::Isometry3d> X_WL;
  linkPoses(q, &X_WL);
  for (const Pair& p : pairs_) {
    if (pairCollides(p, X_WL, which)) return true;
  }
  if (options_.remember_free_states) freeMemo().insert(serial_, q, model_->numVariables());
  return false;
}

double ArmScene::clearance(const double* q, ArmContact* which) const {
  std::vector<Eigen::Isometry3d> X_WL;
  linkPoses(q, &X_WL);
  double best = kInf;
  for (const Pair& p : pairs_) {
    ArmContact c;
    const double d = pairDistance(p, X_WL, &c);
    if (d < best) {
      best = d;
      if (which != nullptr) *which = c;
    }
  }
  return best;
}

double ArmScene::pairWindow(EdgeWork& w, const Pair& p, double tau, int level) const {
  // One side: its tree at `level`, pose, the joints that move it and the
  // rates of its nodes' balls.
  struct Moving {
    Side side;
    Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d X_SW = Eigen::Isometry3d::Identity();
    const std::vector<Mover>* movers = nullptr;
    /// Per node of the side's tree: its ball's rate, once computed.
    EdgeWork::SideScratch* scratch = nullptr;
  };
  const auto make = [&](int link, const std::vector<Mover>* movers) {
    Moving m;
    m.side = side(link, level);
    if (link < 0) return m;
    m.X_WS = w.at->X_WL[static_cast<std::size_t>(link)];
    m.X_SW = m.X_WS.inverse();
    m.movers = movers;
    return m;
  };
  Moving A = p.other < 0 ? make(-1, nullptr) : make(p.link, &p.link_movers);
  Moving B = p.other < 0 ? make(p.link, &p.link_movers) : make(p.other, &p.other_movers);
  for (Moving* m : {&A, &B}) {
    if (m->movers == nullptr) continue;  // the world: no rates
    m->scratch = &w.sides[m == &A ? 0 : 1];
    m->scratch->start(m->side.tree->numNodes());
  }
  // Each node's ball's rate (EdgeWork::ballRate), computed once per node.
  const auto rate = [&](const Moving& m, int node, const Eigen::Vector3d& c_W, double r) {
    if (m.movers == nullptr) return 0.0;
    auto& cached = m.scratch->rates[static_cast<std::size_t>(node)];
    if (cached.first != m.scratch->stamp) cached = {m.scratch->stamp, w.ballRate(*m.movers, c_W, r)};
    return cached.second;
  };
  const double cd = search_distance_;
  double best = tau;
  std::vector<std::pair<int, int>>& stack = w.stack;
  stack.clear();
  stack.push_back({A.side.tree->root(), B.side.tree->root()});
  const bool world_pair = p.other < 0;
  while (!stack.empty()) {
    const auto [ea, eb] = stack.back();
    stack.pop_back();
    const Bvh::Node& na = A.side.tree->node(ea);
    const Bvh::Node& nb = B.side.tree->node(eb);
    // Side A is the world (identity pose) or a link.
    const Eigen::Vector3d ca_W = world_pair ? na.centre : Eigen::Vector3d(A.X_WS * na.centre);
    const Eigen::Vector3d cb_W = B.X_WS * nb.centre;
    const double rho = rate(A, ea, ca_W, na.radius) + rate(B, eb, cb_W, nb.radius);
    // The pair is dropped when any lower bound of the nodes' distance keeps
    // the contact distance over the window: the balls' gap, or each ball's
    // gap to the other node's box (in that node's frame; boxes are far
    // tighter than balls on flat pieces such as shelves). Cheapest first.
    const double need = cd + best * rho + kBvhSlackRel * (na.scale + nb.scale + scale_);
    if ((ca_W - cb_W).norm() - na.radius - nb.radius >= need) continue;
    const auto ballToBox = [](const Bvh::Node& n, const Eigen::Vector3d& c_S, double r) {
      return (n.box.min() - c_S).cwiseMax(c_S - n.box.max()).cwiseMax(0.0).norm() - r;
    };
    if (ballToBox(na, world_pair ? cb_W : Eigen::Vector3d(A.X_SW * cb_W), nb.radius) >= need) continue;
    if (ballToBox(nb, B.X_SW * ca_W, na.radius) >= need) continue;
    if (na.isLeaf() && nb.isLeaf()) {
      DistanceInput in;
      in.a = (*A.side.polytopes)[static_cast<std::size_t>(A.side.tree->leafPiece(ea))];
      in.X_WA = A.X_WS;
      in.b = (*B.side.polytopes)[static_cast<std::size_t>(B.side.tree->leafPiece(eb))];
      in.X_WB = B.X_WS;
      // GJK starts from where the same leaf pair's last search ended (an
      // earlier probe of this edge): the nearest features move little.
      const std::uint64_t key = (static_cast<std::uint64_t>((&p - pairs_.data()) * (kPieceLevel + 1) + level) << 42) |
                                (static_cast<std::uint64_t>(ea) << 21) | static_cast<std::uint64_t>(eb);
      DistanceWarmStart* warm = w.warmStart(key);
      double d = separationLowerBound(in, warm, cd + best * rho, kWindowGapRel);
      if (d <= cd) d = separationLowerBound(in, warm, cd + best * rho);  // no false alarm from the gap
      if (d <= cd) return -1.0;
      if (rho > 0.0) best = std::min(best, (d - cd) / rho);
      continue;
    }
    // Split the larger node (a leaf never); the child nearer the other
    // node is visited first, so that the window shrinks early.
    const bool split_a = nb.isLeaf() || (!na.isLeaf() && na.radius >= nb.radius);
    const Moving& split = split_a ? A : B;
    const Bvh::Node& n = split_a ? na : nb;
    const Eigen::Vector3d& other_W = split_a ? cb_W : ca_W;
    int near = n.left, far = n.right;
    const auto gap = [&](int child) {
      const Bvh::Node& c = split.side.tree->node(child);
      return (split.X_WS * c.centre - other_W).norm() - c.radius;
    };
    if (gap(far) < gap(near)) std::swap(near, far);
    if (split_a) {
      stack.emplace_back(far, eb);
      stack.emplace_back(near, eb);
    } else {
      stack.emplace_back(ea, far);
      stack.emplace_back(ea, near);
    }
  }
  return best;
}

bool ArmScene::rootBallsClear(const EdgeWork& w, const Pair& p, double tau) const {
  const auto ball = [&](int link, const std::vector<Mover>& movers, Eigen::Vector3d* c_W, double* r) {
    const Bvh& tree = *side(link, 0).tree;
    const Bvh::Node& n = tree.node(tree.root());
    *c_W = w.at->X_WL[static_cast<std::size_t>(link)] * n.centre;
    *r = n.radius;
    return w.ballRate(movers, *c_W, n.radius) * tau + kBvhSlackRel * n.scale;
  };
  Eigen::Vector3d ca_W, cb_W;
  double ra = 0.0, rb = 0.0;
  const double reach = ball(p.link, p.link_movers, &ca_W, &ra) + ball(p.other, p.other_movers, &cb_W, &rb);
  const double cd = search_distance_;
  return (ca_W - cb_W).norm() - ra - rb - kBvhSlackRel * scale_ - cd >= reach;
}

bool ArmScene::certify(EdgeWork& w, int p, double a, double b, int depth) const {
  const Pair& pair = pairs_[static_cast<std::size_t>(p)];
  if (a >= w.limit) return false;
  ArmEdgeResult& r = *w.result;
  ++r.intervals;
  const double cd = options_.contact_distance;
  // A bound t of the pair's first contact; contactAt also bounds the search.
  auto report = [&](double t, bool state) {
    r.collides = true;
    if (t < r.fraction) {
      r.fraction = t;
      r.state_collides = state;
      r.contact = {pair.link, -1, pair.other};
    }
    return true;
  };
  auto contactAt = [&](double t, bool state) {
    w.limit = std::min(w.limit, t);
    return report(t, state);
  };
  if (depth > options_.max_depth || b - a < kMinInterval) return contactAt(a, false);
  // kLastValid: a pair clear up to within the tolerance of the best contact
  // so far stops; `a` bounds its own first contact, and the edge's fraction
  // stays at most the tolerance below the best contact.
  if (w.query == EdgeQuery::kLastValid && a >= w.limit - w.tolerance) return report(a, false);
  const double tm = EdgeWork::probeTime(a, b);
  w.poseAt(*this, tm);
  ++r.distance_queries;
  signed char& still = w.still[static_cast<std::size_t>(p)];
  if (still < 0) still = pairRate(p, w.dq.data()) == 0.0 ? 1 : 0;
  if (still == 1) {
    // The pair does not move relative to itself: its distance at tm is its
    // distance on all of [a, b].
    if (pairBound(pair, w.at->X_WL, cd) > cd) return false;
    return contactAt(a, pairCollides(pair, w.at->X_WL, nullptr));
  }
  const double tau = std::max(tm - a, b - tm);
  // 1. Two links whose bounding balls keep the contact distance over all of
  //    [a, b]: clear (the walk's first test, without its set-up).
  if (pair.other >= 0 && rootBallsClear(w, pair, tau)) return false;
  // 2. Each node pair's own motion bound: the window around tm where the
  //    pair keeps the contact distance, up to the farther end of [a, b].
  double window = -1.0;
  for (int level = 0; level <= kPieceLevel && window < 0.0; ++level) {
    if (level == 0 || refines(pair, level)) window = pairWindow(w, pair, tau, level);
  }
  if (window >= tau) return false;  // clear of the contact distance on all of [a, b]
  if (window < 0.0) {
    // 3. A piece pair within the contact distance at tm: a contact. The
    //    first one: certify [a, tm) first.
    const bool state = pairCollides(pair, w.at->X_WL, nullptr);
    contactAt(tm, state);
    if (w.query != EdgeQuery::kValidity) certify(w, p, a, tm, depth + 1);
    return true;
  }
  window *= 1.0 - kRateSlackRel;
  if (tm - window > a && certify(w, p, a, tm - window, depth + 1)) return true;
  if (tm + window < b && certify(w, p, tm + window, b, depth + 1)) return true;
  return false;
}

ArmEdgeResult ArmScene::checkEdge(const double* q0, const double* q1, EdgeQuery query,
                                  double fraction_tolerance) const {
  const int nv = model_->numVariables();
  ArmEdgeResult result;
  if (!(fraction_tolerance >= 0.0 && fraction_tolerance <= 1.0)) {
    throw InvalidInputError("ArmScene::checkEdge: fraction_tolerance must be in [0, 1] (got " +
                            std::to_string(fraction_tolerance) + ")");
  }
  for (int v = 0; v < nv; ++v) {
    if (!std::isfinite(q0[v]) || !std::isfinite(q1[v])) {
      throw InvalidInputError("ArmScene::checkEdge: variable " + model_->variableName(v) + " is not finite");
    }
  }
  thread_local EdgeWork w;
  // 1. Validity (kValidity, and kLastValid first): stops at any contact.
  const bool validity_first = query != EdgeQuery::kFirstContact;
  w.reset(q0, q1, nv, numPairs(), validity_first ? EdgeQuery::kValidity : query, &result);
  const int first = last_contact_.load(std::memory_order_relaxed);
  // The pairs in search order: the pair that found the last contact first
  // (a planner meets the same obstacle again and again), then the others.
  const auto forEachPair = [&](auto&& visit) {
    for (int i = -1; i < numPairs(); ++i) {
      const int p = i < 0 ? first : i;
      if (p < 0 || (i >= 0 && p == first)) continue;
      if (!visit(p)) return;
    }
  };
  if (validity_first) {
    // 1a. The end state: a planner often extends into an obstacle, and one
    //     state check then settles the edge. More states (the middle, the
    //     quarters) cost more than they save before the search, which probes
    //     the middle first anyway (mddual_bench_arm_edges, bookshelf_thin and
    //     cage: 3% to 7% more instructions with the middle).
    //     Skipped for an end state known free (FreeMemo).
    if (!(options_.remember_free_states && freeMemo().contains(serial_, q1, nv))) {
      w.poseAt(*this, 1.0);
      result.end_state_checked = true;
      ArmContact which;
      forEachPair([&](int p) {
        if (!pairCollides(pairs_[static_cast<std::size_t>(p)], w.at->X_WL, &which)) return true;
        last_contact_.store(p, std::memory_order_relaxed);
        result.collides = true;
        result.fraction = 1.0;
        result.state_collides = true;
        result.contact = which;
        return false;
      });
    }
    // 1b. Pair by pair, until a contact.
    if (!result.collides) {
      forEachPair([&](int p) {
        if (certify(w, p, 0.0, 1.0, 0)) {
          last_contact_.store(p, std::memory_order_relaxed);
          return false;
        }
        w.cleared[static_cast<std::size_t>(p)] = 1;  // clear on all of [0, 1]
        return true;
      });
    }
    if (!result.collides && options_.remember_free_states) {
      freeMemo().insert(serial_, q0, nv);
      freeMemo().insert(serial_, q1, nv);
    }
    if (query == EdgeQuery::kValidity || !result.collides) return result;
    // kLastValid on a colliding edge: the contact found bounds the search.
    w.query = query;
    w.limit = result.fraction;
    w.tolerance = fraction_tolerance;
  }
  // 2. The first contact: pair by pair, each searching only before the best
  //    contact so far (EdgeWork::limit).
  forEachPair([&](int p) {
    if (w.cleared[static_cast<std::size_t>(p)] == 0 && certify(w, p, 0.0, std::min(1.0, w.limit), 0)) {
      last_contact_.store(p, std::memory_order_relaxed);
    }
    return true;
  });
  return result;
}

}  // namespace mddual::planning

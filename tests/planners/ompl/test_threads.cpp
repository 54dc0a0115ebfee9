// Concurrent use: the same checkers called from 8 threads at once give the
// answers one thread gives, and the counters add up, on two scenes built in
// code and on the mesh config configs/twistycool; world updates
// made between concurrent runs are seen by every thread. CI runs this
// executable under ThreadSanitizer too (labels tsan / planning-tsan), so it
// stays small.
#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "arm_fixture.h"
#include "mddual/planning/arm_checkers.h"
#include "mddual/planning/clearance.h"
#include "mddual/planning/exact_checking.h"
#include "test_support.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
using testing::Fixture;
constexpr int kThreads = 8;

struct Answers {
  std::vector<char> mdd_state, fcl_state, motion, fcl_motion;
  std::vector<double> last_valid, clearance;
  std::vector<double> last_valid_step;  ///< one step of OMPL's discrete check of the edge (lastValid's tolerance)
  std::vector<double> first_contact;    ///< firstInvalid(kFirstContact).fraction (+inf on a valid edge)
  std::vector<double> separation;       ///< MddStateValidityChecker::clearance (exact distance)
};

struct Workload {
  std::vector<ob::ScopedState<>> states;
  std::vector<std::pair<ob::ScopedState<>, ob::ScopedState<>>> edges;
  std::vector<Eigen::Vector3d> directions;
};

Workload makeWorkload(const Fixture& fx, int states, int edges, std::uint64_t seed) {
  testing::Rng rng(seed);
  Workload w;
  for (int i = 0; i < states; ++i) {
    w.states.emplace_back(fx.space->stateSpace());
    testing::randomState(*fx.space, rng, w.states.back().get());
    // z (unless planar), y, x: the order GCC evaluated the constructor's
    // arguments (C++ leaves it unspecified), kept so seeded workloads stay.
    const double z = fx.space->kind() == SpaceKind::kSE2 ? 0.0 : std::normal_distribution<double>()(rng);
    const double y = std::normal_distribution<double>()(rng);
    const double x = std::normal_distribution<double>()(rng);
    Eigen::Vector3d d(x, y, z);
    w.directions.push_back(d);
  }
  const double extent = (fx.space->bounds().max() - fx.space->bounds().min()).head<2>().norm();
  for (int i = 0; i < edges; ++i) {
    ob::ScopedState<> s1(fx.space->stateSpace()), s2(fx.space->stateSpace());
    testing::randomValidState(*fx.si, *fx.space, rng, s1.get());
    testing::randomEdgeEnd(*fx.space, s1.get(), 0.2 * extent, i % 2 == 1, kPi, rng, s2.get());
    w.edges.emplace_back(s1, s2);
  }
  return w;
}

/// Runs the workload; `offset` rotates the order so threads interleave differently.
Answers run(const Fixture& fx, const FclContinuousMotionValidator& ccd, const Workload& w, std::size_t offset) {
  Answers a;
  const std::size_t ns = w.states.size(), ne = w.edges.size();
  a.mdd_state.resize(ns);
  a.fcl_state.resize(ns);
  a.clearance.resize(ns);
  a.separation.resize(ns);
  a.motion.resize(ne);
  a.fcl_motion.resize(ne);
  a.last_valid.resize(ne);
  a.last_valid_step.resize(ne);
  a.first_contact.resize(ne);
  for (std::size_t k = 0; k < ns; ++k) {
    const std::size_t i = (k + offset) % ns;
    a.mdd_state[i] = fx.mdd_checker->isValid(w.states[i].get());
    a.fcl_state[i] = fx.fcl_checker->isValid(w.states[i].get());
    a.clearance[i] = directedClearance(*fx.mdd, *fx.space, w.states[i].get(), w.directions[i]).distance;
    a.separation[i] = fx.mdd_checker->clearance(w.states[i].get());
  }
  ob::ScopedState<> last(fx.space->stateSpace());
  for (std::size_t k = 0; k < ne; ++k) {
    const std::size_t i = (k + offset) % ne;
    const ob::State* s1 = w.edges[i].first.get();
    const ob::State* s2 = w.edges[i].second.get();
    a.motion[i] = fx.mdd_motion->checkMotion(s1, s2);
    std::pair<ob::State*, double> lv(last.get(), -1.0);
    fx.mdd_motion->checkMotion(s1, s2, lv);
    a.last_valid[i] = lv.second;
    a.last_valid_step[i] = 1.0 / std::max(1u, fx.si->getStateSpace()->validSegmentCount(s1, s2));
    a.first_contact[i] =
        a.motion[i] ? std::numeric_limits<double>::infinity() : fx.mdd_motion->firstInvalid(s1, s2).fraction;
    a.fcl_motion[i] = ccd.checkMotion(s1, s2);
  }
  return a;
}

void expectSame(const Answers& a, const Answers& b, int thread) {
  EXPECT_EQ(a.mdd_state, b.mdd_state) << "thread " << thread;
  EXPECT_EQ(a.fcl_state, b.fcl_state) << "thread " << thread;
  EXPECT_EQ(a.motion, b.motion) << "thread " << thread;
  EXPECT_EQ(a.fcl_motion, b.fcl_motion) << "thread " << thread;
  for (std::size_t i = 0; i < a.last_valid.size(); ++i) {
    EXPECT_NEAR(a.last_valid[i], b.last_valid[i], 1e-12) << "thread " << thread << " edge " << i;
  }
  EXPECT_EQ(a.separation, b.separation) << "thread " << thread;  // deterministic, no warm start
  for (std::size_t i = 0; i < a.clearance.size(); ++i) {
    if (std::isinf(a.clearance[i])) {
      EXPECT_EQ(a.clearance[i], b.clearance[i]) << "thread " << thread << " state " << i;
    } else {
      EXPECT_NEAR(a.clearance[i], b.clearance[i], 1e-9) << "thread " << thread << " state " << i;
    }
  }
}

class Threads : public ::testing::TestWithParam<int> {};

/// The scenes: built in code (planar, mesh), and a mesh config
/// (configs/twistycool: non-convex triangle meshes, both hierarchies, rotating
/// SE(3) edges through the slot; the smallest of the mesh configs).
examples::ExampleScene threadScene(int index) {
  switch (index) {
    case 0: return examples::planarScene(testing::seed(), 30);
    case 1: return examples::meshScene(testing::seed(), 8);
    default: return testing::configScene("twistycool");
  }
}

TEST_P(Threads, SameAnswersFromEightThreadsAsFromOne) {
  const examples::ExampleScene scene = threadScene(GetParam());
  const Fixture fx = testing::makeFixture(scene);
  const FclContinuousMotionValidator ccd(fx.fcl_si, fx.space, fx.fcl);
  // Half the workload on twistycool, whose checks cost more (kept cheap under
  // ThreadSanitizer).
  const int size = GetParam() == 2 ? 1 : 2;
  const Workload w = makeWorkload(fx, 100 * size * testing::scale(), 30 * size * testing::scale(), testing::seed() + 5);
  fx.mdd_checker->resetCounts();
  fx.mdd_motion->resetCounts();
  fx.mdd_motion->resetMotionCounter();
  // On the mesh scene, lastValid as KPIECE gets it (MddMotionValidator::
  // setDiscardedLastValidFraction: (s1, 0) when the state at 0.2 collides).
  if (GetParam() == 1) fx.mdd_motion->setDiscardedLastValidFraction(0.2);
  const Answers reference = run(fx, ccd, w, 0);  // one thread

  std::vector<Answers> answers(kThreads);
  std::vector<std::thread> threads;
  std::atomic<int> ready{0};
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      ready.fetch_add(1);
      while (ready.load() < kThreads) std::this_thread::yield();  // start together
      answers[static_cast<std::size_t>(t)] = run(fx, ccd, w, static_cast<std::size_t>(t) * 37);
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) expectSame(reference, answers[static_cast<std::size_t>(t)], t);

  const std::uint64_t runs = kThreads + 1;
  // isValid is also called by the lastValid back-off: at least one per state per run.
  EXPECT_GE(fx.mdd_checker->counts().state_checks, runs * w.states.size());
  EXPECT_EQ(fx.mdd_motion->counts().motion_checks, runs * 2 * w.edges.size());
  EXPECT_EQ(fx.mdd_motion->getCheckedMotionCount(), runs * 2 * w.edges.size());
  EXPECT_EQ(ccd.counts().motion_checks, runs * w.edges.size());
}

std::string threadSceneName(const ::testing::TestParamInfo<int>& p) {
  switch (p.param) {
    case 0: return "planar";
    case 1: return "mesh";
    default: return "twistycool";
  }
}
INSTANTIATE_TEST_SUITE_P(Scenes, Threads, ::testing::Values(0, 1, 2), threadSceneName);

// The checkers installed by useExactChecking() on a user-made SE(3) x R^1
// space: the same answers from eight threads as from one (the joint leaves its
// bounds on some edges).
TEST(UserSpaceThreads, CompoundSpaceSameAnswersFromEightThreads) {
  const examples::ExampleScene scene = examples::blobScene(testing::seed(), 15);
  auto body = std::make_shared<ob::SE3StateSpace>();
  ob::RealVectorBounds b(3);
  for (unsigned int k = 0; k < 3; ++k) {
    b.setLow(k, scene.bounds.min()[static_cast<int>(k)]);
    b.setHigh(k, scene.bounds.max()[static_cast<int>(k)]);
  }
  body->setBounds(b);
  auto joint = std::make_shared<ob::RealVectorStateSpace>(1);
  joint->setBounds(-1.0, 1.0);
  auto arm = std::make_shared<ob::CompoundStateSpace>();
  arm->addSubspace(body, 1.0);
  arm->addSubspace(joint, 1.0);
  auto si = std::make_shared<ob::SpaceInformation>(arm);
  const ExactChecking exact = useExactChecking(si, scene.robot, scene.world);
  si->setup();

  testing::Rng rng(testing::seed() + 9);
  const PlanningSpacePtr alone = PlanningSpace::se3(scene.bounds);
  auto setJoint = [](ob::State* s, double v) {
    s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(1)->values[0] = v;
  };
  auto bodyOf = [](ob::State* s) { return s->as<ob::CompoundState>()->components[0]; };
  std::vector<std::pair<ob::ScopedState<>, ob::ScopedState<>>> edges;
  const int n = 40 * testing::scale();
  for (int i = 0; i < n; ++i) {
    ob::ScopedState<> s1(arm), s2(arm);
    do {
      testing::randomState(*alone, rng, bodyOf(s1.get()));
      setJoint(s1.get(), std::uniform_real_distribution<double>(-1.0, 1.0)(rng));
    } while (!si->isValid(s1.get()));
    testing::randomEdgeEnd(*alone, bodyOf(s1.get()), 3.0, i % 2 == 1, kPi, rng, bodyOf(s2.get()));
    setJoint(s2.get(), std::uniform_real_distribution<double>(-1.5, 1.5)(rng));
    edges.emplace_back(s1, s2);
  }
  auto runAll = [&](std::size_t offset, std::vector<char>* valid, std::vector<double>* last) {
    ob::ScopedState<> state(arm);
    valid->assign(edges.size(), 0);
    last->assign(edges.size(), -1.0);
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const std::size_t i = (k + offset) % edges.size();
      (*valid)[i] = si->checkMotion(edges[i].first.get(), edges[i].second.get());
      std::pair<ob::State*, double> lv(state.get(), -1.0);
      si->checkMotion(edges[i].first.get(), edges[i].second.get(), lv);
      (*last)[i] = lv.second;
    }
  };
  std::vector<char> valid;
  std::vector<double> last;
  runAll(0, &valid, &last);
  EXPECT_GT(std::count(valid.begin(), valid.end(), 0), 0);
  EXPECT_GT(std::count(valid.begin(), valid.end(), 1), 0);
  std::vector<std::vector<char>> valids(kThreads);
  std::vector<std::vector<double>> lasts(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const auto u = static_cast<std::size_t>(t);
      runAll(u * 7, &valids[u], &lasts[u]);
    });
  }
  for (std::thread& th : threads) th.join();
  for (std::size_t t = 0; t < static_cast<std::size_t>(kThreads); ++t) {
    EXPECT_EQ(valids[t], valid) << "thread " << t;
    for (std::size_t i = 0; i < last.size(); ++i) EXPECT_NEAR(lasts[t][i], last[i], 1e-12) << "thread " << t;
  }
}

/// The MDD answers of a and b (not FCL's, whose scene is not updated).
void expectSameMdd(const Answers& a, const Answers& b, int thread) {
  EXPECT_EQ(a.mdd_state, b.mdd_state) << "thread " << thread;
  EXPECT_EQ(a.motion, b.motion) << "thread " << thread;
  // lastValid's search stops within one discrete step of the best contact it
  // found, and an updated scene's trees (static and overflow) visit the pairs
  // in another order than a rebuilt scene's: the same answer within a step.
  for (std::size_t i = 0; i < a.last_valid.size(); ++i) {
    EXPECT_NEAR(a.last_valid[i], b.last_valid[i], a.last_valid_step[i] + 1e-12) << "thread " << thread << " edge " << i;
    // Translation edges (even i: makeWorkload): b's lastValid within a step
    // before the exact first contact of the scene built from scratch (a),
    // b's from the updated scene's two trees.
    if (i % 2 == 0 && !a.motion[i]) {
      EXPECT_EQ(b.first_contact[i], a.first_contact[i]) << "thread " << thread << " edge " << i;
      EXPECT_LE(b.last_valid[i], a.first_contact[i]) << "thread " << thread << " edge " << i;
      EXPECT_GE(b.last_valid[i], a.first_contact[i] - a.last_valid_step[i] - 1e-6)
          << "thread " << thread << " edge " << i;
    }
  }
  EXPECT_EQ(a.separation, b.separation) << "thread " << thread;
  for (std::size_t i = 0; i < a.clearance.size(); ++i) {
    if (std::isinf(a.clearance[i])) {
      EXPECT_EQ(a.clearance[i], b.clearance[i]) << "thread " << thread << " state " << i;
    } else {
      EXPECT_NEAR(a.clearance[i], b.clearance[i], 1e-9) << "thread " << thread << " state " << i;
    }
  }
}

TEST(ThreadsAndUpdates, UpdatesBetweenConcurrentRunsAreSeenByEveryThread) {
  // Eight threads warm their caches on the scene; then, with no query
  // running, pieces are removed, moved and added; then eight threads again:
  // their answers are those of one thread on a scene built from the updated
  // pieces.
  const examples::ExampleScene scene = examples::planarScene(testing::seed(), 30);
  const Fixture fx = testing::makeFixture(scene);
  const FclContinuousMotionValidator ccd(fx.fcl_si, fx.space, fx.fcl);
  const Workload w = makeWorkload(fx, 100 * testing::scale(), 40 * testing::scale(), testing::seed() + 9);
  const auto concurrently = [&](std::vector<Answers>* answers) {
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back(
          [&, t] { (*answers)[static_cast<std::size_t>(t)] = run(fx, ccd, w, static_cast<std::size_t>(t) * 37); });
    }
    for (std::thread& th : threads) th.join();
  };
  std::vector<Answers> answers(kThreads);
  concurrently(&answers);

  for (int id = 0; id < 5; ++id) fx.mdd->removeWorldPiece(id);
  for (int id = 5; id < 10; ++id) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() << 0.7, -0.4, 0.0;
    fx.mdd->moveWorldPiece(id, X);
  }
  for (int k = 10; k < 15; ++k) {
    scene::Piece piece = fx.mdd->world().pieces()[static_cast<std::size_t>(fx.mdd->world().indexOf(k))];
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() << -1.1, 0.9, 0.0;
    std::vector<Eigen::Vector3d> points;
    for (const Eigen::Vector3d& v : piece.polytope.vertices()) points.push_back(X * v);
    fx.mdd->addWorldPiece(scene::Piece::make(ConvexPolytope::fromPoints(points), piece.kind, "copy"));
  }
  concurrently(&answers);

  examples::ExampleScene rebuilt = scene;
  rebuilt.world = std::make_shared<scene::World>(fx.mdd->world().pieces(), "rebuilt");
  const Fixture fresh = testing::makeFixture(rebuilt);
  const FclContinuousMotionValidator fresh_ccd(fresh.fcl_si, fresh.space, fresh.fcl);
  const Answers reference = run(fresh, fresh_ccd, w, 0);
  for (int t = 0; t < kThreads; ++t) expectSameMdd(reference, answers[static_cast<std::size_t>(t)], t);
  int changed = 0;  // the updates changed some answers (else the test proves little)
  Answers before_updates = run(testing::makeFixture(scene), ccd, w, 0);
  for (std::size_t i = 0; i < w.states.size(); ++i) changed += before_updates.mdd_state[i] != reference.mdd_state[i];
  for (std::size_t i = 0; i < w.edges.size(); ++i) changed += before_updates.motion[i] != reference.motion[i];
  EXPECT_GT(changed, 0);
}

TEST(ArmThreads, SameAnswersFromFourThreadsAsFromOne) {
  // The arm checkers on arm7 (ArmScene, its FCL baseline): states,
  // clearance and edges with lastValid from four threads at once.
  const testing::ArmFixture arm = testing::makeArm();
  const FclArmScene fcl(arm.scene);
  testing::Rng rng(testing::seed());
  std::vector<std::vector<double>> states;
  for (int i = 0; i < 24; ++i) states.push_back(testing::randomConfiguration(*arm.model, rng));
  struct ArmAnswers {
    std::vector<int> state, fcl_state, edge;
    std::vector<double> clearance, fraction;
  };
  auto run = [&](ArmAnswers* out) {
    for (const std::vector<double>& q : states) {
      out->state.push_back(arm.scene->collides(q.data()) ? 1 : 0);
      out->fcl_state.push_back(fcl.collides(q.data()) ? 1 : 0);
      out->clearance.push_back(arm.scene->clearance(q.data()));
    }
    for (std::size_t i = 0; i + 1 < states.size(); i += 2) {
      std::vector<double> q1 = states[i + 1];
      for (std::size_t v = 0; v < q1.size(); ++v) q1[v] = states[i][v] + 0.3 * (q1[v] - states[i][v]);
      const ArmEdgeResult r = arm.scene->checkEdge(states[i].data(), q1.data(), EdgeQuery::kLastValid);
      out->edge.push_back(r.collides ? 1 : 0);
      out->fraction.push_back(r.fraction);
    }
  };
  ArmAnswers reference;
  run(&reference);
  constexpr int kArmThreads = 4;
  std::vector<ArmAnswers> answers(kArmThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kArmThreads; ++t) threads.emplace_back([&, t] { run(&answers[static_cast<std::size_t>(t)]); });
  for (std::thread& th : threads) th.join();
  for (const ArmAnswers& a : answers) {
    EXPECT_EQ(a.state, reference.state);
    EXPECT_EQ(a.fcl_state, reference.fcl_state);
    EXPECT_EQ(a.clearance, reference.clearance);
    EXPECT_EQ(a.edge, reference.edge);
    EXPECT_EQ(a.fraction, reference.fraction);
  }
  EXPECT_GT(std::count(reference.edge.begin(), reference.edge.end(), 1), 0);
}

}  // namespace
}  // namespace mddual::planning

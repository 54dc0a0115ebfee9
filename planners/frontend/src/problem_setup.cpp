#include "mddual/planning/problem_setup.h"

#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/MechanicalWorkOptimizationObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/samplers/GaussianValidStateSampler.h>
#include <ompl/base/samplers/MaximizeClearanceValidStateSampler.h>
#include <ompl/base/samplers/ObstacleBasedValidStateSampler.h>
#include <ompl/base/samplers/UniformValidStateSampler.h>
#include <ompl/base/spaces/RealVectorStateProjections.h>
#include <ompl/tools/config/MagicConstants.h>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <mutex>

#include "mddual/error.h"
#include "mddual/penetration.h"
#include "mddual/planning/fcl_checkers.h"
#include "mddual/planning/planner_factory.h"
#include "mddual/query.h"

namespace mddual::planning {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using ompl::magic::PROJECTION_DIMENSION_SPLITS;

// ---- Timing and counting wrappers ------------------------------------------------

/// Counts the checks of one ProblemSetup and times them once: a motion
/// validator's own state checks (and any other nested check on the same
/// thread) run inside the outer call's time and are not timed again.
class CheckTimer {
 public:
  /// Times the outermost check on this thread.
  class Scope {
   public:
    explicit Scope(CheckTimer& timer) : timer_(timer), outer_(depth()++ == 0) {
      if (outer_) start_ = std::chrono::steady_clock::now();
    }
    ~Scope() {
      --depth();
      if (!outer_) return;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_);
      timer_.nanoseconds.fetch_add(static_cast<std::uint64_t>(ns.count()), std::memory_order_relaxed);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    static int& depth() {
      thread_local int d = 0;
      return d;
    }
    CheckTimer& timer_;
    bool outer_;
    std::chrono::steady_clock::time_point start_;
  };

  void reset() {
    state_checks.store(0, std::memory_order_relaxed);
    motion_checks.store(0, std::memory_order_relaxed);
    nanoseconds.store(0, std::memory_order_relaxed);
  }

  std::atomic<std::uint64_t> state_checks{0};
  std::atomic<std::uint64_t> motion_checks{0};
  std::atomic<std::uint64_t> nanoseconds{0};
};

namespace {

/// Forwards every query to the wrapped checker, counting and timing it.
class TimedStateValidityChecker : public ob::StateValidityChecker {
 public:
  TimedStateValidityChecker(ob::SpaceInformation* si, ob::StateValidityCheckerPtr inner,
                            std::shared_ptr<CheckTimer> timer)
      : ob::StateValidityChecker(si), inner_(std::move(inner)), timer_(std::move(timer)) {
    specs_ = inner_->getSpecs();
  }
  bool isValid(const ob::State* state) const override {
    const CheckTimer::Scope scope(*timer_);
    timer_->state_checks.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state);
  }
  bool isValid(const ob::State* state, double& dist) const override {
    const CheckTimer::Scope scope(*timer_);
    timer_->state_checks.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state, dist);
  }
  bool isValid(const ob::State* state, double& dist, ob::State* valid_state,
               bool& valid_state_available) const override {
    const CheckTimer::Scope scope(*timer_);
    timer_->state_checks.fetch_add(1, std::memory_order_relaxed);
    return inner_->isValid(state, dist, valid_state, valid_state_available);
  }
  double clearance(const ob::State* state) const override {
    const CheckTimer::Scope scope(*timer_);
    return inner_->clearance(state);
  }
  double clearance(const ob::State* state, ob::State* valid_state, bool& valid_state_available) const override {
    const CheckTimer::Scope scope(*timer_);
    return inner_->clearance(state, valid_state, valid_state_available);
  }

 private:
  ob::StateValidityCheckerPtr inner_;
  std::shared_ptr<CheckTimer> timer_;
};

/// Forwards to the wrapped motion validator, counting and timing; keeps
/// OMPL's valid/invalid motion counters (which the benchmark reports).
class TimedMotionValidator : public ob::MotionValidator {
 public:
  TimedMotionValidator(ob::SpaceInformation* si, ob::MotionValidatorPtr inner, std::shared_ptr<CheckTimer> timer)
      : ob::MotionValidator(si), inner_(std::move(inner)), timer_(std::move(timer)) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const CheckTimer::Scope scope(*timer_);
    timer_->motion_checks.fetch_add(1, std::memory_order_relaxed);
    return count(inner_->checkMotion(s1, s2));
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    const CheckTimer::Scope scope(*timer_);
    timer_->motion_checks.fetch_add(1, std::memory_order_relaxed);
    return count(inner_->checkMotion(s1, s2, last_valid));
  }

 private:
  bool count(bool valid) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (valid) {
      ++valid_;
    } else {
      ++invalid_;
    }
    return valid;
  }
  ob::MotionValidatorPtr inner_;
  std::shared_ptr<CheckTimer> timer_;
  mutable std::mutex mutex_;
};

std::string sanitize(const std::string& name) {
  std::string out = name;
  for (char& c : out) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '_' && c != '.' && c != '-') c = '_';
  }
  return out;
}

}  // namespace

// ---- Planner names ------------------------------------------------------------------

std::set<std::string> ourPlannerNames() {
  const std::vector<std::string> names = plannerNames();
  return {names.begin(), names.end()};
}

// ---- Problem ------------------------------------------------------------------------

std::string Problem::cfgName() const {
  return config.file.empty() ? name + ".cfg" : config.file.filename().string();
}

std::shared_ptr<const scene::RigidBody> Problem::robot() const {
  return {scene, &scene->robot};
}

std::shared_ptr<const scene::World> Problem::world() const {
  return {scene, &scene->world};
}

Problem makeProblem(scene::ProblemConfig config, scene::ProblemScene scene) {
  Problem p;
  std::string name = config.name;
  if (name.empty()) name = config.file.stem().string();
  if (name.empty()) name = "problem";
  p.name = sanitize(name);
  p.config = std::move(config);
  p.scene = std::make_shared<const scene::ProblemScene>(std::move(scene));
  return p;
}

Problem loadProblem(const std::filesystem::path& cfg) {
  scene::ProblemConfig config = scene::readProblemConfig(cfg, ourPlannerNames());
  scene::ProblemScene scene = scene::loadProblemScene(config);
  return makeProblem(std::move(config), std::move(scene));
}

namespace {

/// "<cfg>:<line>: " for a planner entry of the cfg, "<cfg>: " for one made
/// in code (line 0: "tiny.cfg:0:" named no line of the file).
std::string specWhere(const std::string& cfg, const scene::PlannerSpec& spec) {
  return spec.line > 0 ? cfg + ":" + std::to_string(spec.line) + ": " : cfg + ": ";
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

/// One state of endpointCollisions: `which` is "start" or "goal". Throws for
/// a position outside the bounds; returns the collision's message, or "".
std::string stateCollision(const Problem& problem, const std::string& which, const Eigen::Isometry3d& X_WR) {
  const scene::ProblemScene& sc = *problem.scene;
  const std::string where = problem.cfgName() + ": the " + which + " state";
  const Eigen::Vector3d p_WR = X_WR.translation();
  const bool planar = sc.space == scene::SpaceKind::kSE2 || sc.space == scene::SpaceKind::kR2;
  const char* const axes[] = {"x", "y", "z"};
  for (int k = 0; k < (planar ? 2 : 3); ++k) {
    if (!(p_WR[k] >= sc.bounds.min()[k] && p_WR[k] <= sc.bounds.max()[k])) {
      throw InvalidInputError(where + " is outside the bounds of the space: " + which + "." + axes[k] + " = " +
                              number(p_WR[k]) + " is not in [" + number(sc.bounds.min()[k]) + ", " +
                              number(sc.bounds.max()[k]) + "] (volume.min." + axes[k] + ", volume.max." + axes[k] +
                              ")");
    }
  }
  // Every (robot piece, world piece) pair whose boxes meet, by the exact
  // test, and the deepest overlap among them (exact penetration depth).
  std::vector<std::string> pairs;
  std::vector<int> candidates;
  double deepest = 0.0;
  std::size_t deepest_pair = 0;
  bool depth_failed = false;
  const auto& robot = sc.robot.pieces();
  const auto& world = sc.world.pieces();
  for (const scene::Piece& r : robot) {
    candidates.clear();
    sc.world.candidates(scene::transformedBox(r.box, X_WR), &candidates);
    for (const int w : candidates) {
      const scene::Piece& piece_w = world[static_cast<std::size_t>(w)];
      IntersectInput in;
      in.a = &r.polytope;
      in.X_WA = X_WR;
      in.b = &piece_w.polytope;
      const IntersectResult x = intersect(in);
      if (!x.intersecting) continue;
      if (x.status != IntersectStatus::kTouching) {
        PenetrationInput pd;
        pd.a = &r.polytope;
        pd.X_WA = X_WR;
        pd.b = &piece_w.polytope;
        double depth = 0.0;
        try {
          depth = penetrationDepth(pd).depth;
        } catch (const std::exception&) {
          depth_failed = true;  // the pair is named all the same; the depth is a hint
        }
        if (depth > deepest) {
          deepest = depth;
          deepest_pair = pairs.size();
        }
      }
      pairs.push_back("robot piece \"" + clipForMessage(r.origin) + "\" " +
                      (x.status == IntersectStatus::kTouching ? "touches" : "overlaps") + " world piece \"" +
                      clipForMessage(piece_w.origin) + "\"");
    }
  }
  if (pairs.empty()) return "";
  std::string named;
  for (std::size_t i = 0; i < pairs.size() && i < kMaxCollisionsNamed; ++i) {
    named += (i == 0 ? "" : "; ") + pairs[i];
  }
  if (pairs.size() > kMaxCollisionsNamed) {
    named += "; and " + std::to_string(pairs.size() - kMaxCollisionsNamed) + " more pairs";
  }
  // Which answer to trust: how deep the worst pair is, and what FCL's
  // discrete check (the fcl checker, OMPL.app's) says of the same pieces.
  const std::string depth = deepest > 0.0
                                ? "the deepest overlap is " + number(deepest) + " (penetration depth of pair " +
                                      std::to_string(deepest_pair + 1) + " of " + std::to_string(pairs.size()) + ")"
                            : depth_failed ? "no penetration depth could be computed"
                                           : "every pair only touches (penetration depth 0)";
  const bool fcl_contact = FclScene(problem.robot(), problem.world()).collides(X_WR);
  return where + " (position " + number(p_WR.x()) + ", " + number(p_WR.y()) + ", " + number(p_WR.z()) +
         ") is in collision: " + named + " (exact check; touching counts as collision); " + depth +
         "; FCL's collide() on the same pieces finds " + (fcl_contact ? "a contact" : "no contact");
}

}  // namespace

std::vector<std::string> endpointCollisions(const Problem& problem) {
  if (!problem.scene) throw InvalidInputError("checkStartAndGoal: the problem has no scene");
  std::vector<std::string> out;
  for (const auto& [which, X_WR] : {std::pair<const char*, const Eigen::Isometry3d*>{"start", &problem.scene->start},
                                    std::pair<const char*, const Eigen::Isometry3d*>{"goal", &problem.scene->goal}}) {
    std::string message = stateCollision(problem, which, *X_WR);
    if (!message.empty()) out.push_back(std::move(message));
  }
  return out;
}

void checkStartAndGoal(const Problem& problem) {
  const std::vector<std::string> collisions = endpointCollisions(problem);
  if (!collisions.empty()) throw InvalidInputError(collisions.front());
}

SpaceKind toPlanningKind(scene::SpaceKind kind) {
  switch (kind) {
    case scene::SpaceKind::kSE2: return SpaceKind::kSE2;
    case scene::SpaceKind::kSE3: return SpaceKind::kSE3;
    case scene::SpaceKind::kR2: return SpaceKind::kR2;
    case scene::SpaceKind::kR3: return SpaceKind::kR3;
  }
  throw InvalidInputError("unknown space kind");
}

// ---- ProblemSetup -------------------------------------------------------------------

ProblemSetup::ProblemSetup(const Problem& problem, const std::string& checker, const SetupOptions& options)
    : problem_(problem), checker_(checker), timer_(std::make_shared<CheckTimer>()) {
  if (!problem_.scene) throw InvalidInputError("ProblemSetup: the problem has no scene");
  const RigidChecker& entry = findRigidChecker(checker);
  const scene::ProblemScene& sc = *problem_.scene;
  const scene::ProblemConfig& cfg = problem_.config;
  const std::string where = problem_.cfgName();

  // 1. The state space.
  const SpaceKind kind = toPlanningKind(sc.space);
  try {
    space_ = PlanningSpace::make(kind, sc.bounds, sc.start.translation().z(), Eigen::Quaterniond(sc.start.linear()));
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(where + ": " + e.what());
  }
  ss_ = std::make_shared<og::SimpleSetup>(space_->stateSpace());
  const ob::SpaceInformationPtr& si = ss_->getSpaceInformation();
  if (kind == SpaceKind::kR2 || kind == SpaceKind::kR3) {
    // The translation-only kinds project on the position, as OMPL's SE(2) and
    // SE(3) defaults do, with OMPL's default cells (extent / 20); explicit
    // cell sizes keep the projection through later set-ups. OMPL's own:
    // R^3 a random 2-D linear map drawn anew at each set-up (projection-based
    // planners such as KPIECE would depend on the draw, differently for each
    // checker); R^2 RealVectorIdentityProjectionEvaluator, which in OMPL
    // 1.5.2 maps dimension * sizeof(double) values (Eigen's assertion fails).
    const int dims = kind == SpaceKind::kR2 ? 2 : 3;
    std::vector<double> cells(static_cast<std::size_t>(dims));
    for (int k = 0; k < dims; ++k) {
      cells[static_cast<std::size_t>(k)] = (sc.bounds.max()[k] - sc.bounds.min()[k]) / PROJECTION_DIMENSION_SPLITS;
    }
    space_->stateSpace()->registerDefaultProjection(std::make_shared<ob::RealVectorLinearProjectionEvaluator>(
        space_->stateSpace(), cells, ob::ProjectionMatrix::Matrix::Identity(dims, dims)));
  }

  // 2. The checker, wrapped.
  installed_ = entry.install({si, space_, problem_.robot(), problem_.world(), options});
  const ob::StateValidityCheckerPtr state_checker = si->getStateValidityChecker();
  const ob::MotionValidatorPtr motion_validator = si->getMotionValidator();
  si->setStateValidityChecker(std::make_shared<TimedStateValidityChecker>(si.get(), state_checker, timer_));
  si->setMotionValidator(std::make_shared<TimedMotionValidator>(si.get(), motion_validator, timer_));
  si->setup();  // the state space's projections (and their parameters) exist from here on

  // 3. Space parameters, then the values the planners' contexts will restore.
  applyParameters(cfg.space_parameters, where + ": [problem] ");
  for (const scene::PlannerSpec& spec : cfg.planners) {
    const std::string at = specWhere(where, spec) + "problem.";
    for (const auto& [key, value] : spec.context) {
      if (key == "sampler") continue;
      std::string current;
      if (!si->params().getParam(key, current)) {
        throw InvalidInputError(at + key + ": not a parameter of OMPL's space information");
      }
      baseline_.emplace(key, current);
    }
  }
  for (const auto& [key, value] : cfg.space_parameters) {
    if (key == "sampler") baseline_sampler_ = value;
  }

  // 4. Start, goal, objective.
  ob::ScopedState<> start(space_->stateSpace());
  ob::ScopedState<> goal(space_->stateSpace());
  try {
    space_->setPose(sc.start, start.get());
    space_->setPose(sc.goal, goal.get());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(where + ": start or goal: " + e.what());
  }
  // The checker must find them free too: checkStartAndGoal's exact test can
  // call a state free that a checker, deciding contact within its precision
  // (relative to the size of the pieces), calls touching, e.g. beside a world
  // triangle 1e12 across; every run would then end at "invalid start".
  // With allow_invalid_endpoints the runs go on all the same (the planners
  // then solve nothing with this checker, which the report shows).
  for (const auto& [which, state] : {std::pair<const char*, const ob::State*>{"start", start.get()},
                                     std::pair<const char*, const ob::State*>{"goal", goal.get()}}) {
    if (options.allow_invalid_endpoints || state_checker->isValid(state)) continue;
    throw InvalidInputError(where + ": the " + which + " state is in collision for the " + checker +
                            " checker (OMPL's planners would refuse it in every run), though the bench's exact " +
                            "check of each pair of pieces may find it free: the checkers decide contact within " +
                            "a precision relative to the size of the pieces, and pieces of very different sizes " +
                            "(a huge world triangle beside a small robot) make that precision coarse");
  }
  const double threshold = cfg.threshold.value_or(scene::kDefaultGoalThreshold);
  if (!(threshold > 0.0)) throw InvalidInputError(where + ": threshold must be positive");
  ss_->setStartAndGoalStates(start, goal, threshold);
  if (!cfg.objective.empty()) {
    ob::OptimizationObjectivePtr objective;
    if (cfg.objective == "length") {
      objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    } else if (cfg.objective == "max_min_clearance") {
      objective = std::make_shared<ob::MaximizeMinClearanceObjective>(si);
    } else if (cfg.objective == "mechanical_work") {
      objective = std::make_shared<ob::MechanicalWorkOptimizationObjective>(si);
    } else {
      throw InvalidInputError(where + ": unknown objective '" + cfg.objective +
                              "' (length, max_min_clearance, mechanical_work)");
    }
    if (cfg.objective_threshold) objective->setCostThreshold(ob::Cost(*cfg.objective_threshold));
    ss_->setOptimizationObjective(objective);
  }
}

ProblemSetup::~ProblemSetup() = default;

void ProblemSetup::setSampler(const std::string& name, const std::string& where) {
  const ob::SpaceInformationPtr& si = ss_->getSpaceInformation();
  if (name.empty()) {
    si->clearValidStateSamplerAllocator();
    return;
  }
  ob::ValidStateSamplerAllocator alloc;
  if (name == "uniform") {
    alloc = [](const ob::SpaceInformation* s) { return std::make_shared<ob::UniformValidStateSampler>(s); };
  } else if (name == "gaussian") {
    alloc = [](const ob::SpaceInformation* s) { return std::make_shared<ob::GaussianValidStateSampler>(s); };
  } else if (name == "obstacle_based") {
    alloc = [](const ob::SpaceInformation* s) { return std::make_shared<ob::ObstacleBasedValidStateSampler>(s); };
  } else if (name == "max_clearance") {
    alloc = [](const ob::SpaceInformation* s) { return std::make_shared<ob::MaximizeClearanceValidStateSampler>(s); };
  } else {
    throw InvalidInputError(where + "sampler: unknown sampler '" + name +
                            "' (uniform, gaussian, obstacle_based, max_clearance)");
  }
  si->setValidStateSamplerAllocator(alloc);
}

void ProblemSetup::applyParameters(const std::vector<std::pair<std::string, std::string>>& params,
                                   const std::string& where) {
  const ob::SpaceInformationPtr& si = ss_->getSpaceInformation();
  for (const auto& [key, value] : params) {
    if (key == "sampler") {
      setSampler(value, where);
      continue;
    }
    if (!si->params().hasParam(key)) {
      std::vector<std::string> names;
      si->params().getParamNames(names);
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      throw InvalidInputError(where + key + ": not a parameter of OMPL's space information (its parameters: " + known +
                              ", and sampler)");
    }
    bool ok = false;
    try {
      ok = si->params().setParam(key, value);
    } catch (const std::exception&) {
      ok = false;
    }
    if (!ok) throw InvalidInputError(where + key + ": OMPL rejects the value '" + value + "'");
  }
  si->setup();  // recompute what depends on them (the longest valid segment, projections)
}

void ProblemSetup::applyPlannerContext(const scene::PlannerSpec& spec) {
  const ob::SpaceInformationPtr& si = ss_->getSpaceInformation();
  for (const auto& [key, value] : baseline_) si->params().setParam(key, value);
  setSampler(baseline_sampler_, problem_.cfgName() + ": [problem] ");
  applyParameters(spec.context, specWhere(problem_.cfgName(), spec) + "problem.");
}

ob::PlannerPtr ProblemSetup::makePlanner(const scene::PlannerSpec& spec) const {
  const std::string at = specWhere(problem_.cfgName(), spec);
  ob::PlannerPtr planner;
  try {
    planner = planning::makePlanner(spec.name, ss_->getSpaceInformation(), spec.params);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(at + e.what());
  } catch (const std::exception& e) {  // OMPL's own exceptions from a parameter's setter
    throw InvalidInputError(at + "planner '" + spec.name + "': " + e.what());
  }
  bool named = false;
  for (const auto& [key, value] : spec.params) named = named || key == "name";
  if (!named) planner->setName(spec.name);
  return planner;
}

std::string ProblemSetup::plannerWhere(const scene::PlannerSpec& spec) const {
  return specWhere(problem_.cfgName(), spec) + "planner '" + spec.name + "': ";
}

void ProblemSetup::setDiscardedLastValidFraction(double fraction) {
  if (installed_.set_discarded_last_valid_fraction) installed_.set_discarded_last_valid_fraction(fraction);
}

CheckStats ProblemSetup::stats() const {
  CheckStats s;
  s.state_checks = timer_->state_checks.load(std::memory_order_relaxed);
  s.motion_checks = timer_->motion_checks.load(std::memory_order_relaxed);
  s.seconds = static_cast<double>(timer_->nanoseconds.load(std::memory_order_relaxed)) * 1e-9;
  const CheckerCounts own = installed_.counts();
  s.pair_queries = own.pair_queries;
  s.sub_edges = own.sub_edges;
  return s;
}

void ProblemSetup::resetStats() {
  timer_->reset();
  installed_.reset_counts();
}

}  // namespace mddual::planning

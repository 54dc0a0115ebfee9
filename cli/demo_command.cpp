// `mddual demo`: the first thing to run. Places generated polytopes (the
// MDD-DUAL paper's P1..P6, a box, a cube, a triangle) in random poses chosen to
// give every kind of answer (separated, touching, penetrating, no contact),
// answers each query with MDD-DUAL and with the brute-force reference, and
// prints one line per query and a summary. --emit-jsonl writes the same
// queries in `mddual query`'s input format.
#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "commands.h"
#include "jsonl.h"
#include "mddual/brute_force.h"
#include "mddual/error.h"
#include "mddual/generators.h"
#include "mddual/query.h"

namespace mddual::cli {
namespace {

using generators::Points;
using generators::Rng;

struct DemoOptions {
  std::uint64_t seed = 1;
  int pairs = 15;
  std::string emit_jsonl;
};

/// How a pair is placed; the comments say which answer the placement gives.
enum class Placement {
  kTowards,    // apart, direction roughly toward A: separated, t_lo > 0
  kAway,       // apart, direction roughly away from A: separated, t_hi < 0
  kOverlap,    // centres close together: penetrating
  kMiss,       // apart, direction perpendicular to the offset: no contact
  kVertex,     // a vertex of B on a vertex of A, a plane between them: touching
  kFaceFace,   // axis-aligned cubes face to face (exact coordinates): touching
  kOnTopFace,  // a triangle lying on the top face of a cube: touching
};

struct PlanEntry {
  const char* a;
  const char* b;
  Placement placement;
};

// The paper's benchmark pairs (P1,P2), (P1,P3), (P4,P5), (P4,P6), (Pi,Pi) and
// flat and boxy shapes; cycled when more pairs are asked for.
constexpr PlanEntry kPlan[] = {
    {"P1", "P2", Placement::kTowards},      {"P1", "P3", Placement::kOverlap},
    {"cube", "cube", Placement::kFaceFace}, {"P4", "P5", Placement::kAway},
    {"P4", "P6", Placement::kMiss},         {"P1", "P1", Placement::kVertex},
    {"P2", "P2", Placement::kOverlap},      {"cube", "tri", Placement::kOnTopFace},
    {"P3", "P3", Placement::kTowards},      {"P5", "P5", Placement::kMiss},
    {"P6", "P6", Placement::kOverlap},      {"tri", "box", Placement::kTowards},
    {"tri", "cube", Placement::kOverlap},   {"P2", "P6", Placement::kVertex},
    {"box", "P3", Placement::kMiss},
};
constexpr int kPlanSize = static_cast<int>(sizeof(kPlan) / sizeof(kPlan[0]));

/// Body-frame points of a named shape, centred at the origin.
Points shapePoints(const std::string& name) {
  Points p;
  if (name == "cube") {
    p = generators::box(Eigen::Vector3d(1.0, 1.0, 1.0));
  } else if (name == "box") {
    p = generators::box(Eigen::Vector3d(2.0, 1.5, 0.75));
  } else if (name == "tri") {
    p = generators::triangle(Eigen::Vector3d(-0.75, -0.5, 0.0), Eigen::Vector3d(0.875, -0.25, 0.0),
                             Eigen::Vector3d(-0.125, 0.75, 0.0));
  } else {
    p = generators::paperPolytope(name);
  }
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : p) centre += x;
  centre /= static_cast<double>(p.size());
  if (name != "cube" && name != "tri") {  // keep the exact coordinates of the touching scenes
    for (Eigen::Vector3d& x : p) x -= centre;
  }
  return p;
}

Points transformed(const Points& p, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& offset) {
  Points out;
  out.reserve(p.size());
  for (const Eigen::Vector3d& x : p) out.push_back(rotation * x + offset);
  return out;
}

double radiusOf(const Points& p) {
  double r = 0.0;
  for (const Eigen::Vector3d& x : p) r = std::max(r, x.norm());
  return r;
}

const Eigen::Vector3d& supportPoint(const Points& p, const Eigen::Vector3d& d) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (d.dot(p[i]) > d.dot(p[best])) best = i;
  }
  return p[best];
}

/// One query: world-frame point sets (identity poses) and a direction.
struct Scene {
  std::string name_a;
  std::string name_b;
  Points a;
  Points b;
  Eigen::Vector3d direction;
};

Scene makeScene(const PlanEntry& entry, std::map<std::string, Points>* shapes, Rng& rng) {
  auto shape = [&](const std::string& name) -> const Points& {
    auto it = shapes->find(name);
    if (it == shapes->end()) it = shapes->emplace(name, shapePoints(name)).first;
    return it->second;
  };
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  auto between = [&](double lo, double hi) { return lo + (hi - lo) * uniform(rng); };
  Scene s{entry.a, entry.b, {}, {}, Eigen::Vector3d::Zero()};
  const Eigen::Vector3d d = generators::randomUnitVector(rng);
  const double length = between(0.5, 3.0);  // directions need not be unit length
  switch (entry.placement) {
    case Placement::kFaceFace:  // B's face x = -1 lies on A's face x = +1
      s.a = shape(entry.a);
      s.b = transformed(shape(entry.b), Eigen::Matrix3d::Identity(),
                        Eigen::Vector3d(2.0, std::round(between(-0.9, 0.9) * 8.0) / 8.0, 0.25));
      s.direction = length * d;
      return s;
    case Placement::kOnTopFace:  // the triangle in the plane z = 1 of A's top face
      s.a = shape(entry.a);
      s.b = transformed(shape(entry.b), Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.5, -0.25, 1.0));
      s.direction = length * d;
      return s;
    default: break;
  }
  s.a = transformed(shape(entry.a), generators::randomRotation(rng), Eigen::Vector3d::Zero());
  const Points b_at_origin = transformed(shape(entry.b), generators::randomRotation(rng), Eigen::Vector3d::Zero());
  const double ra = radiusOf(s.a);
  const double rb = radiusOf(b_at_origin);
  const Eigen::Vector3d wobble = 0.1 * generators::randomUnitVector(rng);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  switch (entry.placement) {
    case Placement::kTowards:
      offset = between(1.05, 1.5) * (ra + rb) * d;
      s.direction = length * (wobble - d);
      break;
    case Placement::kAway:
      offset = between(1.05, 1.5) * (ra + rb) * d;
      s.direction = length * (wobble + d);
      break;
    case Placement::kOverlap:
      offset = between(0.0, 0.4) * std::min(ra, rb) * d;
      s.direction = length * generators::randomUnitVector(rng);
      break;
    case Placement::kMiss:  // the line stays farther than ra + rb from B's centre
      offset = between(1.1, 1.5) * (ra + rb) * d;
      s.direction = length * d.cross(generators::randomUnitVector(rng)).normalized();
      break;
    case Placement::kVertex:
      offset = supportPoint(s.a, d) - supportPoint(b_at_origin, -d);
      s.direction = length * (0.5 * generators::randomUnitVector(rng) - d);
      break;
    default: break;
  }
  s.b = transformed(b_at_origin, Eigen::Matrix3d::Identity(), offset);
  return s;
}

Json pointsJson(const Points& p) {
  Json out = Json::array();
  for (const Eigen::Vector3d& x : p) out.push_back(Json::array({x.x(), x.y(), x.z()}));
  return out;
}

bool sameValue(double x, double y, double tol) {
  if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y);
  if (std::isinf(x) || std::isinf(y)) return x == y;
  return std::abs(x - y) <= tol;
}

std::string formatNumber(double x, const char* never) {
  if (!std::isfinite(x)) return never;
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%+.9f", x);
  return buffer;
}

/// Runs one scene by both methods and prints its line; true if they agree.
bool runScene(int number, const Scene& scene, std::map<ContactStatus, int>* counts) {
  const ConvexPolytope a = ConvexPolytope::fromPoints(scene.a);
  const ConvexPolytope b = ConvexPolytope::fromPoints(scene.b);
  DirectionalInput input;
  input.a = &a;
  input.b = &b;
  input.s_W = scene.direction;
  const MddResult dual = mdd(input);
  const MddResult brute = bruteForceMdd(input);
  const ToiResult toi_dual = toi(input);
  const ToiResult toi_brute = bruteForceToi(input);
  const int faces_of_m = MinkowskiDifference::build(a, Eigen::Isometry3d::Identity(), b, Eigen::Isometry3d::Identity())
                             .polytope.numFaces();
  // Scene scale as the library measures it (defaults.h, kTouchRel).
  const double scale = std::max({a.radius(), b.radius(), (a.centroid() - b.centroid()).norm()});
  const double tol = 1e-9 * scale;
  const bool agree = dual.status == brute.status && sameValue(dual.distance, brute.distance, tol) &&
                     toi_dual.status == toi_brute.status && sameValue(toi_dual.toi, toi_brute.toi, tol);
  ++(*counts)[dual.status];
  const Eigen::Vector3d u = scene.direction.normalized();
  const std::string pair = scene.name_a + "/" + scene.name_b;
  std::printf("%3d  %-9s (%+.3f,%+.3f,%+.3f)  %-11s %13s  %-11s %13s  %13s %13s  %7d %6d  %s\n", number, pair.c_str(),
              u.x(), u.y(), u.z(), toString(dual.status), formatNumber(dual.distance, "-").c_str(),
              toString(brute.status), formatNumber(brute.distance, "-").c_str(),
              formatNumber(toi_dual.toi, "never").c_str(), formatNumber(toi_brute.toi, "never").c_str(),
              dual.stats.totalFaces(), faces_of_m, agree ? "yes" : "NO");
  return agree;
}

void printHeader() {
  std::printf(
      "MDD, the signed minimum directional distance of two convex polytopes A (fixed) and B\n"
      "(moving) along a direction s: how far B must translate along s to touch A (> 0: separated;\n"
      "a backward move counts as positive too), 0 when they touch, minus the shorter translation\n"
      "along the line that separates them when they overlap (< 0), none when no translation along\n"
      "the line makes them touch. toi is the first contact moving forward along s.\n"
      "dual = MDD-DUAL (searches the faces of M = A - B without building M); brute = builds M.\n"
      "visited = faces of M that MDD-DUAL evaluated (counted once per search phase, so a small\n"
      "boxy M can be visited more times than it has faces); faces = faces of M (coplanar merged).\n\n");
  std::printf("%3s  %-9s %-22s  %-11s %13s  %-11s %13s  %13s %13s  %7s %6s  %s\n", "#", "A/B", "direction s (unit)",
              "dual", "mdd", "brute", "mdd", "toi dual", "toi brute", "visited", "faces", "agree");
}

void runDemo(const DemoOptions& options) {
  std::ofstream jsonl;
  if (!options.emit_jsonl.empty()) {
    jsonl.open(options.emit_jsonl, std::ios::out | std::ios::trunc);
    if (!jsonl.is_open()) throw FatalError("cannot open output file '" + options.emit_jsonl + "'");
  }
  Rng rng(options.seed);
  std::map<std::string, Points> shapes;
  std::map<ContactStatus, int> counts;
  printHeader();
  int agreed = 0;
  for (int k = 0; k < options.pairs; ++k) {
    const Scene scene = makeScene(kPlan[k % kPlanSize], &shapes, rng);
    if (jsonl.is_open()) {
      const Json line{{"id", "demo-" + std::to_string(k + 1)},
                      {"a", pointsJson(scene.a)},
                      {"b", pointsJson(scene.b)},
                      {"direction", Json::array({scene.direction.x(), scene.direction.y(), scene.direction.z()})}};
      jsonl << line.dump() << '\n';
    }
    try {
      if (runScene(k + 1, scene, &counts)) ++agreed;
    } catch (const Error& e) {
      std::printf("%3d  %s/%s  error: %s\n", k + 1, scene.name_a.c_str(), scene.name_b.c_str(), e.what());
    }
    std::fflush(stdout);
  }
  if (jsonl.is_open() && !jsonl.flush()) throw FatalError("cannot write '" + options.emit_jsonl + "'");
  std::printf("\nstatuses (dual): %d separated, %d touching, %d penetrating, %d no_contact\n",
              counts[ContactStatus::kSeparated], counts[ContactStatus::kTouching], counts[ContactStatus::kPenetrating],
              counts[ContactStatus::kNoContact]);
  std::printf("%d queries, %d agree with the brute force\n", options.pairs, agreed);
  std::fflush(stdout);
  if (agreed != options.pairs) throw CLI::RuntimeError(1);
}

}  // namespace

void registerDemoCommand(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand("demo", "a short demo: generated polytope pairs by MDD-DUAL and by brute force");
  sub->add_option("--seed", options->seed, "random seed (std::mt19937_64)")->capture_default_str();
  sub->add_option("--pairs", options->pairs, "number of queries")->check(CLI::Range(1, 100000))->capture_default_str();
  sub->add_option("--emit-jsonl", options->emit_jsonl, "also write the queries as `mddual query` input to FILE")
      ->option_text("FILE");
  sub->footer("Exit status: 0 if every answer agrees with the brute force, 1 otherwise.");
  sub->callback([options] { runDemo(*options); });
}

}  // namespace mddual::cli

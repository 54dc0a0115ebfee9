// Timing and accuracy of one method on one pair's queries.
//
// Timing: every query is timed on its own with std::chrono::steady_clock
// (clock_gettime through the vDSO, 1 ns resolution, ~20 ns per call here),
// and the median cost of an empty timed region (timerOverheadNs) is subtracted.
// Per-query timing, rather than timing blocks of queries, is what gives real
// percentiles: the cost of a query varies with the placement (separated
// queries stop after one ray, overlapping ones need two) and a block average
// would hide that spread. The timed region holds only the call into the
// library (mdd/toi or the peer's cast); the answer is converted and checked
// outside it.
//
// The machine is shared (2 cores, other builds and tests running), so a
// query can be descheduled while it is timed. Each method therefore runs its
// whole query set `passes` times (default 3) and a query's time is the fastest
// of its passes; the passes are interleaved at the level of whole sets, so no
// query is repeated back to back (no branch predictor or cache training on
// one query), and a warm sequence is replayed from its primer each pass
// (every pass times the same cache states). The answers are those of the
// first pass (all the methods are deterministic).
//
// Accuracy: answers are compared with the exact reference of scene.h. Errors
// are absolute differences divided by the scene scale 10 (every polytope lies
// within radius 5).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "peers.h"
#include "scene.h"

namespace mddual::bench {

inline constexpr double kSceneScale = 10.0;
/// Agreement required of an exact method (relative to kSceneScale).
inline constexpr double kExactRelTol = 1e-9;
/// A "large" error (relative to kSceneScale): 1e-3, i.e. 0.01 world units.
inline constexpr double kLargeErrRel = 1e-3;

/// One method's answer to one query.
struct Answer {
  double value = std::numeric_limits<double>::quiet_NaN();  ///< mdd distance, or toi (+inf: never)
  bool contact = false;                                     ///< mdd: the line meets M; toi: value is finite
  bool error = false;                                       ///< the method threw
  int faces = -1;                                           ///< ours: faces of M evaluated (SearchStats::totalFaces)
  int ee_faces = -1;                                        ///< ours: EE faces evaluated (SearchStats::ee_edge_faces)
  int centre_iterations = 0, steps = 0, rays = 0, support_vertices = 0;  ///< ours: SearchStats
  std::string message;                                                   ///< exception text
};

/// Raw measurements of one method on one query set.
struct MethodRun {
  std::string name;  ///< mdd_cold, toi_warm, bullet_gjk, ...
  bool ours = false;
  bool is_mdd = false;     ///< answers are signed MDDs (else toi)
  bool warm = false;       ///< ran on the warm sequences
  std::vector<double> ns;  ///< time per query (NaN if it threw)
  std::vector<Answer> answers;
};

/// Median of the time of an empty timed region (two back-to-back now()).
double timerOverheadNs();

/// mddual::mdd() or mddual::toi() on the cold queries (no WarmStart) or on
/// the warm sequences (one WarmStart per sequence, filled by its primer).
/// Each query set is run `passes` times; a query's time is its fastest pass
/// (see the file comment).
MethodRun runOurs(const PairScene& scene, bool mdd, bool warm, int passes, double overhead_ns);
/// A peer's toi on the cold queries.
MethodRun runPeer(const PairScene& scene, ToiPeer& peer, int passes, double overhead_ns);

/// Summary of a MethodRun against the references.
struct Summary {
  int queries = 0;
  double median_us = 0.0, p90_us = 0.0, p99_us = 0.0, mean_us = 0.0, max_us = 0.0;
  /// Time over the queries that start separated (reference toi > 0 or never):
  /// the case every peer is designed for.
  int separated_queries = 0;
  double separated_median_us = 0.0, separated_p90_us = 0.0;
  /// Time over the queries that start in contact (reference toi 0).
  double in_contact_median_us = 0.0, in_contact_p90_us = 0.0;
  /// Errors: over the queries where both answers are finite, except (toi) the
  /// trivially exact ones where both are 0.
  int compared = 0;
  double max_err = 0.0, median_err = 0.0, mean_err = 0.0;
  int inexact = 0;    ///< errors above kExactRelTol (relative)
  int large_err = 0;  ///< errors above kLargeErrRel (relative)
  /// exceptions + nans + false_never + false_hit
  int failures = 0;
  int exceptions = 0, nans = 0;
  int false_never = 0;  ///< reported no contact where the reference has one
  int touch_never = 0;  ///< of false_never: B touches A at the start and moves into it
  ///< (the overlapping starts reported as never are overlap_never below)
  int false_hit = 0;           ///< reported a contact where the reference has none
  int ambiguous_accepted = 0;  ///< toi 0 vs never at a touching contact: either accepted
  /// Ours: answers off by more than kExactRelTol * kSceneScale, or a different
  /// classification (strict, no ambiguity allowance).
  int mismatches = 0;
  /// Queries starting in overlap (reference toi 0, origin strictly in M):
  /// what the method returned.
  int overlap_queries = 0, overlap_zero = 0, overlap_positive = 0, overlap_never = 0;
  /// Ours: mean percentage of the faces / EE faces of M evaluated, over the
  /// queries whose line meets M; and the mean counts.
  double faces_visited_pct = -1.0, ee_faces_visited_pct = -1.0;
  double faces_visited_mean = -1.0, ee_faces_visited_mean = -1.0;
  /// Ours: mean SearchStats counters over the same queries.
  double centre_iterations_mean = -1.0, steps_mean = -1.0, rays_mean = -1.0, support_vertices_mean = -1.0;
  std::vector<std::string> examples;  ///< first failures/mismatches, with the query
};

Summary summarize(const PairScene& scene, const MethodRun& run, int max_examples);

/// Linear-interpolated percentile (p in [0, 100]) of the finite values.
double percentile(std::vector<double> values, double p);

}  // namespace mddual::bench

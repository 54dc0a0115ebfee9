// Tolerances and iteration limits of mddual, in one place.
//
// Every tolerance is *relative*: it is multiplied by a length scale of the
// query (see each entry) so that the same numbers work for bodies of size 1e-3
// and 1e3 and for offsets of 1e4. All values are dimensionless unless noted.
#pragma once

namespace mddual::defaults {

// ---- Hull construction (ConvexPolytope::fromPoints) -------------------------

// Supported range of coordinates (world units). The queries form products of
// up to four lengths (cross products of edge vectors dotted with differences,
// squared norms of those): with every coordinate at most kMaxCoordinate in
// magnitude and every body at least kMinSize across, such products stay
// within [1e-200, 1e200], far from double's overflow (1.8e308) and underflow
// (2.2e-308). Points beyond are rejected with InvalidInputError; poses whose
// translation exceeds kMaxCoordinate likewise.
inline constexpr double kMaxCoordinate = 1e50;
inline constexpr double kMinSize = 1e-50;

// A point set whose thickness (largest distance to the best plane through it)
// is at most kFlatToleranceRel times its diameter is treated as a flat polygon.
// Reason: qhull's own round-off (~1e-15 of the coordinates' magnitude) fails on
// such sets; projecting them onto their plane moves no point by more than this
// relative amount, which is far below the 1e-9 accuracy the queries promise.
inline constexpr double kFlatToleranceRel = 1e-10;

// Points whose distance to the line through the two farthest points is at most
// this fraction of the diameter are collinear: not a polytope (an error).
inline constexpr double kCollinearToleranceRel = 1e-10;

// Adjacent hull facets whose planes agree this closely (every vertex of both
// within kCoplanarToleranceRel * diameter of the merged plane) are merged into
// one face (paper section VI-C). qhull already merges exact coplanar facets;
// this catches round-off leftovers.
inline constexpr double kCoplanarToleranceRel = 1e-12;

// ---- Support queries ---------------------------------------------------------

// Polytopes with more vertices than this get a Dobkin-Kirkpatrick hierarchy,
// which fills their direction table (one O(log n) descent per cell) and serves
// supportVertexHierarchy(); smaller ones climb from vertex 0 there. On random
// hulls a cold query evaluates fewer vertices with the hierarchy from about 300
// vertices on (65 against 92 at 1,000; docs/results/tuning.md).
inline constexpr int kHierarchyMinVertices = 256;

// The hierarchy removes independent sets of vertices of degree at most this
// (the classic DK bound keeps a constant fraction of vertices removable).
inline constexpr int kHierarchyMaxRemovedDegree = 8;

// The hierarchy stops when a level has at most this many vertices; its top is
// scanned exhaustively.
inline constexpr int kHierarchyTopSize = 16;

// Support values within kSupportTieRel * (scale of the polytope) of the
// maximum count as ties: the supporting feature is then an edge or a face,
// and the search includes the features around every tied vertex.
inline constexpr double kSupportTieRel = 1e-12;

// ---- Directional queries (mdd / toi / intersect) ------------------------------

// Query length scale: L = max(radius(A), radius(B), |centre(A) - centre(B)|).
// A placement is "touching" when the signed distance is within kTouchRel * L
// of zero; the same tolerance decides that a line grazes M (lies in a
// supporting plane of M) rather than crossing its interior.
inline constexpr double kTouchRel = 1e-10;

// Two unit directions whose cross product is shorter than this are parallel
// (edge pairs that cannot form an EE face, lines parallel to a plane).
inline constexpr double kParallelSin = 1e-12;

// Contact points: the point x of M where the line leaves it is split as
// x = a - b over the vertices of A and B within delta of their support values
// in the contact normal's direction. delta starts at kSupportTieRel * L and
// grows by kContactTieGrowth until the polygon those vertices span in the
// contact plane holds x (within kTouchRel * L), up to kContactTieMaxRel * L.
// Reason: a face that is planar only to round-off (nearly coplanar hull
// facets; points rounded far from the origin, about 1e-16 of the offset,
// 1e-8 L at an offset of 1e8 L) has vertices below the support value by more
// than the tie tolerance. a is a point of A and b lies within about 2 delta
// of B. The search uses the same widening before it accepts a face with a
// tie, or nearly one (support gap or arc margin below kContactTieMaxRel), as
// the exit face: faces hidden by a too narrow tie set are evaluated too.
// Dimensionless.
inline constexpr double kContactTieGrowth = 10.0;
inline constexpr double kContactTieMaxRel = 1e-6;

// An EE face of M whose two edges have a sine below this between them has a
// normal known only to about 1e-16 / sine (relative): the search then takes
// its offset from the support values of A and B along that normal (two
// support queries) instead of from the edges' points, so that the plane
// still bounds M. Above it the normal's error is below 1e-10, within the
// touching tolerance. Dimensionless.
inline constexpr double kEdgeEdgeWellConditionedSin = 1e-6;

// Iteration cap of the 2D portal refinement that finds the centre of duality.
// On a polytope it terminates in at most (vertices of the projection) steps;
// the cap only guards against non-termination from round-off.
inline constexpr int kMaxCentreIterations = 256;

// Iteration cap of each hill-climbing phase (faces of M visited in one phase).
// Each step strictly increases the objective, so a phase cannot exceed the
// number of faces of M; the cap guards against round-off cycling.
inline constexpr int kMaxSearchSteps = 100000;

// The centre of duality is a convex combination w0 g + w1 m1 + w2 m2 of an
// interior point g of M and two boundary points; the portal refinement goes on
// until w0 is at least this (or the portal reaches the boundary of M'), so that
// the centre keeps some distance from the boundary of M. Dimensionless.
inline constexpr double kCentreMinWeight = 1e-3;

}  // namespace mddual::defaults

// ---- Penetration depth, width, polyhedral metrics (penetration.h) ---------------

namespace mddual::defaults {

// Default accuracy parameter of the (1 + delta)-approximate penetration depth
// (Approx-Separation). Dimensionless. The grid has about 2 pi / delta
// directions (one ray shot each): about 60 at 0.1.
inline constexpr double kApproxPdDelta = 0.1;

// Default delta of the shallow-penetration method. It trades the grid of its
// first phase (an approximation with delta / 4: about 8 pi / delta
// directions) against the breadth-first search over the facets of M within
// (1 + delta / 2) times the estimate. Dimensionless.
inline constexpr double kShallowPdDelta = 0.5;

// Range accepted for delta. Below kMinPdDelta the grid would exceed ~60,000
// directions for kApprox (a quarter of that delta for kShallow); above
// kMaxPdDelta the bound (1 + delta) says nothing useful. Dimensionless.
inline constexpr double kMinPdDelta = 1e-4;
inline constexpr double kMaxPdDelta = 1e3;

// Exact penetration depth, Gaussian-map walk: a vertex region of -B that is
// left "behind" the current point by more than this fraction of the edge
// length (x . (b_w - b_v) < -slack |b_w - b_v|, x a unit normal) means the
// walk lost track of the region, which exact arithmetic never does; the arc
// is then redone by testing it against every edge of B. Round-off in x . d is
// ~1e-16 |d|, so this only fires on a real inconsistency.
inline constexpr double kPdWalkSlackRel = 1e-10;

// Exact penetration depth, Gaussian-map walk: an arc of A (a great-circle
// arc of at most a half circle) enters each convex vertex region of -B at
// most once, so the walk along it takes at most |V(B)| steps; it is cut at
// |V(B)| + kPdWalkExtraSteps (round-off cycling between tied regions) and the
// arc redone by testing.
inline constexpr int kPdWalkExtraSteps = 16;

// A polyhedral metric K must be centrally symmetric about the origin: every
// vertex v needs a vertex within kMetricSymmetryRel * (largest |v|) of -v.
// Dimensionless; loose enough for coordinates printed with 10 digits.
inline constexpr double kMetricSymmetryRel = 1e-9;

}  // namespace mddual::defaults

// ---- Separation distance (distance.h) ---------------------------------------------

namespace mddual::defaults {

// GJK stops when its upper bound |v| (a point of M) and its certified lower
// bound (v . w / |v|, w the support point of M toward the origin) differ by
// at most kDistanceGapRel * L (L: the pair's length scale, as kTouchRel).
// Round-off in those dot products is ~1e-15 L, so the gap closes on every
// non-degenerate input; a GJK run that stalls above it (its support point is
// already in its simplex) is redone exactly from every feature pair.
inline constexpr double kDistanceGapRel = 1e-11;

// Iteration cap of one GJK run. GJK on polytopes terminates in at most
// (vertices of M) steps and usually in under 20; the cap only guards against
// round-off cycling (the query then falls back to every feature pair).
inline constexpr int kMaxGjkIterations = 200;

}  // namespace mddual::defaults

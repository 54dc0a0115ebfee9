// Construction of ConvexPolytope from a point set:
//   1. validation (empty, non-finite, out of the supported range, collinear),
//      and the local frame: the points relative to their bounding box's centre,
//   2. flatness test against the least-squares plane,
//   3. hull: qhull in 3D (or 2D for flat sets), coplanar facets merged,
//   4. topology: edges with their Gaussian-arc wedges, vertex adjacency,
//   5. the Dobkin-Kirkpatrick hierarchy for large polytopes (support.cpp).
// prism() builds an extruded convex polygon the same way, its faces made
// directly instead of by a 3D hull (phases 1, 3 and 4 of its own).
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

#include "mddual/defaults.h"
#include "mddual/error.h"
#include "mddual/polytope.h"
#include "qhull_wrapper.h"

namespace mddual {

/// Fills a ConvexPolytope's arrays; a friend so the public class stays lean.
class PolytopeBuilder {
 public:
  explicit PolytopeBuilder(ConvexPolytope* out) : out_(out) {}

  void build(const std::vector<Eigen::Vector3d>& points_P);
  void buildPrism(const std::vector<Eigen::Vector3d>& base_P, const Eigen::Vector3d& axis_P, double half_height);

 private:
  struct Face {
    Eigen::Vector3d normal;
    std::vector<int> loop;  // indices into points, counter-clockwise about normal
  };

  std::vector<Eigen::Vector3d> validateAndCentre(const std::vector<Eigen::Vector3d>& points_P);
  void buildFlat(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal);
  void buildSolid(const std::vector<Eigen::Vector3d>& points, double diameter);
  void finish(const std::vector<Eigen::Vector3d>& points, std::vector<Face> faces);

  ConvexPolytope* out_;
  const std::vector<Eigen::Vector3d>* input_P_ = nullptr;  ///< the caller's points (frame P)
  std::vector<Eigen::Vector3d> corners_P_;                 ///< prism(): the corners made (frame P)
};

namespace {

std::string pointText(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  return s.str();
}

/// Unit vector orthogonal to n (n unit).
Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& n) {
  const Eigen::Vector3d t = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(t).normalized();
}

}  // namespace

ConvexPolytope ConvexPolytope::fromPoints(const std::vector<Eigen::Vector3d>& points_P) {
  ConvexPolytope polytope;
  PolytopeBuilder(&polytope).build(points_P);
  return polytope;
}

ConvexPolytope ConvexPolytope::prism(const std::vector<Eigen::Vector3d>& base_points_P, const Eigen::Vector3d& axis_P,
                                     double half_height) {
  ConvexPolytope polytope;
  PolytopeBuilder(&polytope).buildPrism(base_points_P, axis_P, half_height);
  return polytope;
}

namespace {

/// Throws InvalidInputError naming the first non-finite or out-of-range point.
void checkPoints(const std::vector<Eigen::Vector3d>& points_P) {
  for (size_t i = 0; i < points_P.size(); ++i) {
    if (!points_P[i].allFinite()) {
      throw InvalidInputError("polytope: point " + std::to_string(i) + " " + pointText(points_P[i]) +
                              " has a non-finite coordinate");
    }
    if (points_P[i].cwiseAbs().maxCoeff() > defaults::kMaxCoordinate) {
      std::ostringstream msg;
      msg << "polytope: point " << i << " " << pointText(points_P[i])
          << " is out of the supported range: coordinates must be at most " << defaults::kMaxCoordinate
          << " in magnitude (the arithmetic would overflow)";
      throw InvalidInputError(msg.str());
    }
  }
}

}  // namespace

void PolytopeBuilder::build(const std::vector<Eigen::Vector3d>& points_P) {
  // Phase 1: validation and the local frame.
  if (points_P.empty()) throw InvalidInputError("polytope: the point set is empty");
  checkPoints(points_P);
  if (points_P.size() < 3) {
    throw DegenerateGeometryError("polytope: " + std::to_string(points_P.size()) +
                                  " point(s) given; at least three non-collinear points are needed");
  }
  const std::vector<Eigen::Vector3d> points = validateAndCentre(points_P);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double diameter = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - mean;
    cov += d * d.transpose();
    diameter = std::max(diameter, d.norm());
  }
  diameter *= 2.0;  // an upper bound on the diameter, within a factor 2
  if (!(diameter > 0.0)) {
    throw DegenerateGeometryError("polytope: all " + std::to_string(points.size()) + " points coincide at " +
                                  pointText(points_P[0]));
  }
  // Phase 2: the least-squares line and plane (eigenvalues ascending).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d axis = eig.eigenvectors().col(2);
  const Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
  double off_line = 0.0;
  double off_plane = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - mean;
    off_line = std::max(off_line, (d - d.dot(axis) * axis).norm());
    off_plane = std::max(off_plane, std::abs(d.dot(normal)));
  }
  if (off_line <= defaults::kCollinearToleranceRel * diameter) {
    // Within the tolerance of the points' extent: a box 1e12 long and 0.8
    // wide is collinear here (said so, with both sizes: it read as an error
    // in the input's coordinates).
    std::ostringstream msg;
    msg.precision(3);
    msg << "polytope: all " << points.size() << " points are collinear (fewer than three non-collinear points): "
        << "they lie within " << off_line << " of a line and span about " << diameter << ", below "
        << defaults::kCollinearToleranceRel << " of their extent";
    throw DegenerateGeometryError(msg.str());
  }
  // Phase 3 and 4: hull and topology.
  if (off_plane <= defaults::kFlatToleranceRel * diameter) {
    buildFlat(points, normal);
  } else {
    buildSolid(points, diameter);
  }
  // Phase 5: hierarchy for fast cold support queries.
  out_->buildHierarchy();
  out_->buildDirectionTable();
}

std::vector<Eigen::Vector3d> PolytopeBuilder::validateAndCentre(const std::vector<Eigen::Vector3d>& points_P) {
  // The local frame L: P translated to the centre of the bounding box. For a
  // body far from P's origin, p - centre is exact (both of nearly equal
  // magnitude), so everything below sees the body's shape at full precision.
  input_P_ = &points_P;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points_P) box.extend(p);
  out_->p_PL_ = box.center();
  std::vector<Eigen::Vector3d> points;
  points.reserve(points_P.size());
  for (const Eigen::Vector3d& p : points_P) points.push_back(p - out_->p_PL_);
  const double extent = box.sizes().maxCoeff();
  if (extent > 0.0 && extent < defaults::kMinSize) {
    std::ostringstream msg;
    msg.precision(3);
    msg << "polytope: the points span only " << extent << ", below the smallest supported body size "
        << defaults::kMinSize << " (the arithmetic would underflow)";
    throw InvalidInputError(msg.str());
  }
  return points;
}

void PolytopeBuilder::buildPrism(const std::vector<Eigen::Vector3d>& base_P, const Eigen::Vector3d& axis_P,
                                 double half_height) {
  // Phase 1: validation.
  if (base_P.size() < 3) {
    throw DegenerateGeometryError("polytope prism: " + std::to_string(base_P.size()) +
                                  " base point(s) given; at least three non-collinear points are needed");
  }
  checkPoints(base_P);
  const double axis_norm = axis_P.norm();
  if (!std::isfinite(axis_norm) || !(axis_norm > 0.0)) {
    throw InvalidInputError("polytope prism: the axis " + pointText(axis_P) + " is not a finite nonzero vector");
  }
  if (!std::isfinite(half_height) || !(half_height > 0.0)) {
    std::ostringstream msg;
    msg << "polytope prism: the half height " << half_height << " is not a finite positive number";
    throw InvalidInputError(msg.str());
  }
  // Phase 2: the base's 2D hull in the plane normal to the axis, relative to
  // the base's bounding-box centre c (precision far from P's origin).
  const Eigen::Vector3d n = axis_P / axis_norm;
  const Eigen::Vector3d e1 = anyOrthogonal(n);
  const Eigen::Vector3d e2 = n.cross(e1);
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : base_P) box.extend(p);
  const Eigen::Vector3d c = box.center();
  std::vector<Eigen::Vector2d> planar;
  planar.reserve(base_P.size());
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Eigen::Vector3d& p : base_P) {
    const Eigen::Vector3d d = p - c;
    planar.emplace_back(d.dot(e1), d.dot(e2));
    lo = std::min(lo, d.dot(n));
    hi = std::max(hi, d.dot(n));
  }
  lo -= half_height;
  hi += half_height;
  // A base collinear in the plane has no area (qhull's 2D hull would fail
  // unlocated): the farthest point from base 0, then the largest distance
  // from the line through the two.
  std::size_t far = 0;
  for (std::size_t i = 1; i < planar.size(); ++i) {
    if ((planar[i] - planar[0]).norm() > (planar[far] - planar[0]).norm()) far = i;
  }
  const Eigen::Vector2d line = planar[far] - planar[0];
  double off_line = 0.0;
  for (const Eigen::Vector2d& q : planar) {
    const Eigen::Vector2d d = q - planar[0];
    off_line = std::max(off_line, std::abs(line.x() * d.y() - line.y() * d.x()));
  }
  if (!(off_line > defaults::kCollinearToleranceRel * line.squaredNorm())) {
    throw DegenerateGeometryError("polytope prism: the " + std::to_string(base_P.size()) +
                                  " base points are collinear seen along the axis " + pointText(n));
  }
  const std::vector<int> ring = detail::hull2d(planar, "polytope prism (base)");
  // Phase 3: corners (bottom j at j, top j at m + j) and faces, built
  // directly: qhull's merging of the two large coplanar faces made fromPoints
  // quadratic in the base's size (5,000 corners: 5 s; here 40 ms, 200,000 corners 2 s).
  const int m = static_cast<int>(ring.size());
  corners_P_.clear();
  for (double h : {lo, hi}) {
    for (int j : ring) corners_P_.push_back(c + planar[j].x() * e1 + planar[j].y() * e2 + h * n);
  }
  try {
    checkPoints(corners_P_);
  } catch (const InvalidInputError& e) {
    std::ostringstream msg;
    msg << "polytope prism: the half height " << half_height << " takes its corners out of range (" << e.what() << ")";
    throw InvalidInputError(msg.str());
  }
  const std::vector<Eigen::Vector3d> points = validateAndCentre(corners_P_);
  std::vector<Face> faces;
  faces.reserve(static_cast<std::size_t>(m) + 2);
  Face top{n, {}};
  Face bottom{-n, {}};
  for (int j = 0; j < m; ++j) {
    top.loop.push_back(m + j);
    bottom.loop.push_back(m - 1 - j);
  }
  faces.push_back(std::move(top));
  faces.push_back(std::move(bottom));
  for (int j = 0; j < m; ++j) {
    // The ring runs counter-clockwise about n, so edge d's outward normal is
    // d x n; its face's loop, counter-clockwise about that normal, is
    // bottom j, bottom j+1, top j+1, top j.
    const int k = (j + 1) % m;
    const Eigen::Vector2d d = planar[ring[k]] - planar[ring[j]];
    const Eigen::Vector3d normal = (d.y() * e1 - d.x() * e2).normalized();
    faces.push_back({normal, {j, k, m + k, m + j}});
  }
  finish(points, std::move(faces));
  // Phase 4: the direction table, without the hierarchy: its levels are 3D
  // hulls of vertex subsets, which have the same two large coplanar faces
  // (4.9 s of the 5,000-gon's 5.2 s). Support queries then climb from the
  // table's start vertex, which is exact on any convex polytope.
  out_->buildDirectionTable();
}

void PolytopeBuilder::buildFlat(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d e1 = anyOrthogonal(normal);
  const Eigen::Vector3d e2 = normal.cross(e1);
  std::vector<Eigen::Vector2d> planar;
  planar.reserve(points.size());
  for (const Eigen::Vector3d& p : points) planar.emplace_back(p.dot(e1), p.dot(e2));
  // A triangle (every piece of a triangle mesh) is its own hull: order its
  // corners counter-clockwise without a qhull run (qhull's set-up dominated
  // the loading of 40,000-triangle meshes). The collinearity test above
  // guarantees a nonzero area.
  std::vector<int> ring;
  if (planar.size() == 3) {
    const Eigen::Vector2d d1 = planar[1] - planar[0];
    const Eigen::Vector2d d2 = planar[2] - planar[0];
    ring = d1.x() * d2.y() - d1.y() * d2.x() > 0.0 ? std::vector<int>{0, 1, 2} : std::vector<int>{0, 2, 1};
  } else {
    ring = detail::hull2d(planar, "polytope (flat polygon)");
  }
  out_->flat_ = true;
  // Two faces with the same loop: +normal counter-clockwise, -normal reversed.
  std::vector<Face> faces(2);
  faces[0].normal = normal;
  faces[0].loop = ring;
  faces[1].normal = -normal;
  faces[1].loop.assign(ring.rbegin(), ring.rend());
  finish(points, std::move(faces));
}

void PolytopeBuilder::buildSolid(const std::vector<Eigen::Vector3d>& points, double diameter) {
  // qhull merges coplanar facets as it builds the hull (paper VI-C), within
  // kCoplanarToleranceRel of the diameter: merging inside qhull keeps the
  // topology valid, where merging its output afterwards did not on points
  // with round-off above qhull's own estimate (vertex differences of bodies
  // far from the origin).
  const std::vector<detail::HullFacet> facets =
      detail::hull3d(points, "polytope", defaults::kCoplanarToleranceRel * diameter);
  std::vector<Face> faces;
  faces.reserve(facets.size());
  for (const detail::HullFacet& f : facets) faces.push_back({f.normal, f.vertices});
  finish(points, std::move(faces));
}

void PolytopeBuilder::finish(const std::vector<Eigen::Vector3d>& points, std::vector<Face> faces) {
  ConvexPolytope& p = *out_;
  // Drop boundary points that are not corners: for solids, a vertex of fewer
  // than three faces (on an edge or inside a face); for flat polygons, a
  // vertex where the loop goes straight on. Each point is dropped from every
  // loop or from none: a solid's vertex of three or more faces stays in all of
  // them even where one loop goes straight on there (nearly coplanar facets
  // meeting on an edge of a third face), since dropping it from that loop
  // alone left the edges on either side of it with one face each.
  std::vector<int> face_count(points.size(), 0);
  for (const Face& f : faces)
    for (int v : f.loop) ++face_count[v];
  for (Face& f : faces) {
    std::vector<int> kept;
    const size_t k = f.loop.size();
    for (size_t i = 0; i < k; ++i) {
      const Eigen::Vector3d& a = points[f.loop[(i + k - 1) % k]];
      const Eigen::Vector3d& b = points[f.loop[i]];
      const Eigen::Vector3d& c = points[f.loop[(i + 1) % k]];
      const bool straight = p.flat_ && (b - a).cross(c - b).norm() <= 1e-14 * (b - a).norm() * (c - b).norm();
      const bool hidden = !p.flat_ && face_count[f.loop[i]] < 3;
      if (!straight && !hidden) kept.push_back(f.loop[i]);
    }
    f.loop = std::move(kept);
  }
  // Renumber the surviving vertices compactly.
  std::vector<int> index_of(points.size(), -1);
  for (const Face& f : faces) {
    for (int v : f.loop) {
      if (index_of[v] < 0) {
        index_of[v] = static_cast<int>(p.vertices_L_.size());
        p.vertices_L_.push_back(points[v]);
        p.vertices_P_.push_back((*input_P_)[static_cast<size_t>(v)]);
      }
    }
  }
  const int nv = p.numVertices();
  // Faces.
  p.face_vertex_begin_.push_back(0);
  for (const Face& f : faces) {
    double h = -std::numeric_limits<double>::infinity();
    for (int v : f.loop) {
      p.face_vertex_ids_.push_back(index_of[v]);
      h = std::max(h, f.normal.dot(points[v]));
    }
    p.face_vertex_begin_.push_back(static_cast<int>(p.face_vertex_ids_.size()));
    p.face_normals_P_.push_back(f.normal);
    p.face_offsets_L_.push_back(h);
  }
  // Edges: each directed edge a->b of face f (counter-clockwise about n(f))
  // meets its reverse in exactly one other face g. dir = b - a carries n(f) to
  // n(g) counter-clockwise, so face_left = f and face_right = g.
  std::map<std::pair<int, int>, int> directed;  // (a, b) -> face
  for (int f = 0; f < p.numFaces(); ++f) {
    const IndexRange loop = p.faceVertices(f);
    for (int i = 0; i < loop.size(); ++i) {
      const std::pair<int, int> key{loop[i], loop[(i + 1) % loop.size()]};
      if (!directed.emplace(key, f).second) {
        throw NumericalError("polytope: hull edge " + std::to_string(key.first) + "->" + std::to_string(key.second) +
                             " appears twice");
      }
    }
  }
  std::vector<std::vector<std::pair<int, int>>> incident(nv);  // vertex -> (neighbour, edge)
  for (const auto& [key, f] : directed) {
    const auto rev = directed.find({key.second, key.first});
    if (rev == directed.end()) {
      throw NumericalError("polytope: hull edge " + std::to_string(key.first) + "-" + std::to_string(key.second) +
                           " borders only one face");
    }
    if (key.first > key.second && !p.flat_) continue;  // each undirected edge once
    if (p.flat_ && f != 0) continue;                   // flat: take face 0's direction
    ConvexPolytope::Edge e;
    e.v0 = key.first;
    e.v1 = key.second;
    e.face_left = f;
    e.face_right = rev->second;
    e.dir_P = (p.vertices_L_[e.v1] - p.vertices_L_[e.v0]).normalized();
    e.wedge_left_P = e.dir_P.cross(p.face_normals_P_[e.face_left]);
    e.wedge_right_P = p.face_normals_P_[e.face_right].cross(e.dir_P);
    const int id = p.numEdges();
    p.edges_.push_back(e);
    incident[e.v0].push_back({e.v1, id});
    incident[e.v1].push_back({e.v0, id});
  }
  // Face edge lists, aligned with the face loops.
  std::map<std::pair<int, int>, int> edge_of;
  for (int e = 0; e < p.numEdges(); ++e) {
    const ConvexPolytope::Edge& edge = p.edges_[e];
    edge_of[{std::min(edge.v0, edge.v1), std::max(edge.v0, edge.v1)}] = e;
  }
  for (int f = 0; f < p.numFaces(); ++f) {
    const IndexRange loop = p.faceVertices(f);
    for (int i = 0; i < loop.size(); ++i) {
      const int a = loop[i];
      const int b = loop[(i + 1) % loop.size()];
      p.face_edge_ids_.push_back(edge_of.at({std::min(a, b), std::max(a, b)}));
    }
  }
  const int euler = nv - p.numEdges() + p.numFaces();
  if (euler != 2) {
    throw NumericalError("polytope: hull topology fails Euler's formula (V - E + F = " + std::to_string(euler) + ")");
  }
  // Vertex adjacency (CSR).
  p.vertex_adj_begin_.push_back(0);
  for (int v = 0; v < nv; ++v) {
    for (const auto& [w, e] : incident[v]) {
      p.vertex_neighbors_.push_back(w);
      p.vertex_edges_.push_back(e);
    }
    p.vertex_adj_begin_.push_back(static_cast<int>(p.vertex_neighbors_.size()));
  }
  std::vector<std::vector<int>> faces_of(nv);
  for (int f = 0; f < p.numFaces(); ++f)
    for (int v : p.faceVertices(f)) faces_of[v].push_back(f);
  p.vertex_face_begin_.push_back(0);
  for (int v = 0; v < nv; ++v) {
    p.vertex_face_ids_.insert(p.vertex_face_ids_.end(), faces_of[v].begin(), faces_of[v].end());
    p.vertex_face_begin_.push_back(static_cast<int>(p.vertex_face_ids_.size()));
  }
  // Centroid (mean of vertices: interior, or relative interior when flat).
  p.centroid_L_.setZero();
  for (const Eigen::Vector3d& v : p.vertices_L_) p.centroid_L_ += v;
  p.centroid_L_ /= nv;
  p.centroid_P_ = p.centroid_L_ + p.p_PL_;
  p.radius_ = 0.0;
  for (const Eigen::Vector3d& v : p.vertices_L_) p.radius_ = std::max(p.radius_, (v - p.centroid_L_).norm());
}

}  // namespace mddual

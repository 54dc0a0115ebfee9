// ConvexPolytope: a convex polytope in its own body frame, built once from a
// point set (the convex hull, via qhull) and then posed many times by the
// queries without rebuilding.
//
// Frames: the polytope's body frame "P" is the frame of the points given to
// fromPoints(); the public accessors vertex(), vertices(), faceOffset() and
// centroid() answer in P (p_PV is vertex V of polytope P in frame P). The
// polytope also keeps everything in a local frame "L": P translated to the
// centre of the input points' bounding box (p_PL). The queries work in L, so
// that a body far from its frame's origin (a 1 cm part at 100 m, a unit box at
// 1e8) is as well conditioned as one at the origin: subtracting the centre
// from coordinates of nearly equal magnitude is exact (Sterbenz), so the
// local coordinates carry every bit of the input's relative geometry.
// Directions (face normals, edge directions and wedges) are the same in P and
// L (a translation).
//
// What the search needs (paper sections II-B, VI-C):
//   - faces with unit outward normals n_P and offsets h (n . x <= h on P), the
//     coplanar facets of the hull merged into one face;
//   - edges with their two faces and the edge's arc on the Gaussian sphere,
//     stored as a wedge test (see Edge);
//   - vertex adjacency (neighbour vertices, incident edges, incident faces);
//   - support-vertex queries: hill climbing from a hint or from a direction
//     table, which a Dobkin-Kirkpatrick hierarchy fills (O(log n) per query;
//     polytopes without one, small ones and prism()'s, fill it by climbing
//     from cell to cell).
//
// Flat polygons (all points coplanar) are valid polytopes: they have two faces
// (normals +N and -N, same vertex loop), and every boundary edge joins those
// two faces; its Gaussian arc is the half great circle through the edge's
// outward in-plane normal.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace mddual {

/// A contiguous read-only range of indices (C++17 stand-in for std::span).
class IndexRange {
 public:
  IndexRange(const int* first, const int* last) : first_(first), last_(last) {}
  const int* begin() const { return first_; }
  const int* end() const { return last_; }
  int size() const { return static_cast<int>(last_ - first_); }
  int operator[](int i) const { return first_[i]; }

 private:
  const int* first_;
  const int* last_;
};

/// Counters a support query can report (for statistics, never for control).
struct SupportStats {
  int vertices_visited = 0;  ///< vertices whose dot product was evaluated
};

class ConvexPolytope {
 public:
  /// An edge between vertices v0 and v1, shared by faces face_left and
  /// face_right.
  ///
  /// dir_P is the unit edge direction, oriented so that turning about dir_P
  /// counter-clockwise carries n(face_left) to n(face_right) through the
  /// edge's normal cone. The normal cone of the edge (its Gaussian arc, as a
  /// 2D wedge in the plane orthogonal to dir_P) is then
  ///     { x orthogonal to dir_P : x . wedge_left_P >= 0 and x . wedge_right_P >= 0 }
  /// with wedge_left_P = dir_P x n(face_left) and wedge_right_P = n(face_right)
  /// x dir_P. This form also covers the half-circle arcs of flat polygons,
  /// whose two face normals are opposite. Arc crossing (paper VI-B) becomes:
  /// x = dir_a x dir_b lies in both wedges (up to sign).
  struct Edge {
    int v0 = -1;
    int v1 = -1;
    int face_left = -1;
    int face_right = -1;
    Eigen::Vector3d dir_P = Eigen::Vector3d::Zero();
    Eigen::Vector3d wedge_left_P = Eigen::Vector3d::Zero();
    Eigen::Vector3d wedge_right_P = Eigen::Vector3d::Zero();
    /// The face across this edge from face f (one of its two faces).
    int otherFace(int f) const { return face_left == f ? face_right : face_left; }
  };

  /// Builds the convex hull of points_P (frame P). Throws InvalidInputError
  /// for an empty set or a non-finite coordinate (naming the point index) and
  /// DegenerateGeometryError when fewer than three points are non-collinear.
  static ConvexPolytope fromPoints(const std::vector<Eigen::Vector3d>& points_P);

  /// Builds a prism: the convex hull of base_points_P seen along axis_P (a
  /// convex polygon in the plane normal to the axis), extruded along the unit
  /// axis from min_i(axis . p_i) - half_height to max_i(axis . p_i) +
  /// half_height; it holds every base point's segment p +- half_height axis.
  /// Its faces are made directly: a base of 5,000 corners takes 40 ms (200,000:
  /// 2 s), where fromPoints on the same corners is quadratic in the
  /// size of the two large coplanar faces (qhull's merging). Throws
  /// InvalidInputError for a non-finite or out-of-range point, a zero or
  /// non-finite axis or a half_height that is not finite and positive, and
  /// DegenerateGeometryError when the base is collinear seen along the axis.
  static ConvexPolytope prism(const std::vector<Eigen::Vector3d>& base_points_P, const Eigen::Vector3d& axis_P,
                              double half_height);

  int numVertices() const { return static_cast<int>(vertices_P_.size()); }
  int numEdges() const { return static_cast<int>(edges_.size()); }
  int numFaces() const { return static_cast<int>(face_normals_P_.size()); }

  /// True when all vertices lie in one plane (a flat polygon with two faces).
  bool isFlat() const { return flat_; }

  /// Vertex v in the body frame P (one of the input points).
  const Eigen::Vector3d& vertex(int v) const { return vertices_P_[v]; }
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_P_; }

  /// Unit outward normal and offset of face f in frame P: the face lies in
  /// n . x = h and the polytope in n . x <= h.
  const Eigen::Vector3d& faceNormal(int f) const { return face_normals_P_[f]; }
  double faceOffset(int f) const { return face_offsets_L_[f] + face_normals_P_[f].dot(p_PL_); }

  // ---- The local frame L (see the file comment) ----
  /// Origin of the local frame in P: the centre of the input points' bounding
  /// box. X_PL is the translation by p_PL().
  const Eigen::Vector3d& p_PL() const { return p_PL_; }
  /// Vertex v in the local frame (p_PV - p_PL, computed from the input point).
  const Eigen::Vector3d& localVertex(int v) const { return vertices_L_[v]; }
  const std::vector<Eigen::Vector3d>& localVertices() const { return vertices_L_; }
  /// Offset of face f in the local frame: the face lies in n . x = h_L.
  double localFaceOffset(int f) const { return face_offsets_L_[f]; }
  /// centroid() in the local frame.
  const Eigen::Vector3d& localCentroid() const { return centroid_L_; }
  /// The face's vertices, counter-clockwise seen from outside (along -n).
  IndexRange faceVertices(int f) const { return range(face_vertex_begin_, face_vertex_ids_, f); }
  /// The face's edges in loop order: edge k joins faceVertices(f)[k] and [k+1].
  IndexRange faceEdges(int f) const { return range(face_vertex_begin_, face_edge_ids_, f); }

  const Edge& edge(int e) const { return edges_[e]; }

  IndexRange vertexNeighbors(int v) const { return range(vertex_adj_begin_, vertex_neighbors_, v); }
  /// Edges incident to v, in the same order as vertexNeighbors(v).
  IndexRange vertexEdges(int v) const { return range(vertex_adj_begin_, vertex_edges_, v); }
  IndexRange vertexFaces(int v) const { return range(vertex_face_begin_, vertex_face_ids_, v); }

  /// Mean of the vertices: an interior point (relative interior if flat).
  const Eigen::Vector3d& centroid() const { return centroid_P_; }
  /// Largest distance from centroid() to a vertex.
  double radius() const { return radius_; }

  /// Index of a vertex v maximising d_P . vertex(v) (the same vertex in any
  /// frame that differs from P by a translation; evaluated in L). Hill-climbs from the
  /// better of `hint` (when >= 0) and the direction table's vertex for d_P (a
  /// cube map of directions, about one cell per vertex, filled with the
  /// Dobkin-Kirkpatrick hierarchy where there is one). Exact for any nonzero
  /// d_P; a hint other than -1 outside [0, numVertices()) is an
  /// InvalidInputError (as are such `start`s and `v`s below); when several
  /// vertices tie, any of them may be returned.
  /// When `gap` is given it receives d_P . v minus the best value among v's
  /// neighbours (>= 0): a gap within tolerance means the supporting feature
  /// is an edge or a face rather than the vertex alone.
  int supportVertex(const Eigen::Vector3d& d_P, int hint = -1, SupportStats* stats = nullptr,
                    double* gap = nullptr) const;

  /// Hill climbing only (from `start`), for tests and benchmarks.
  int supportVertexHillClimb(const Eigen::Vector3d& d_P, int start, SupportStats* stats = nullptr,
                             double* gap = nullptr) const;
  /// Hierarchy descent only (falls back to hill climbing from vertex 0 when the
  /// polytope is too small to have a hierarchy), for tests and benchmarks.
  int supportVertexHierarchy(const Eigen::Vector3d& d_P, SupportStats* stats = nullptr, double* gap = nullptr) const;
  /// Levels of the Dobkin-Kirkpatrick hierarchy (0 when there is none).
  int hierarchyDepth() const { return static_cast<int>(levels_.size()); }

  /// Appends to `out` every vertex w with d_P . vertex(w) >= d_P . vertex(v) -
  /// tol, found by a walk from the support vertex v over tied neighbours; these
  /// span the supporting feature (vertex, edge or face) in direction d_P.
  void supportTies(const Eigen::Vector3d& d_P, int v, double tol, std::vector<int>* out) const;

 private:
  friend class PolytopeBuilder;

  /// One level of the Dobkin-Kirkpatrick hierarchy: a subset of the vertices
  /// of the level below, with the adjacency of its own hull.
  struct HierarchyLevel {
    std::vector<int> vertex_ids;       ///< original vertex index of each local vertex
    std::vector<int> below;            ///< local index of each vertex in the level below
    std::vector<int> adjacency_begin;  ///< CSR offsets into adjacency
    std::vector<int> adjacency;        ///< local neighbour indices
    std::vector<int> removed_begin;    ///< CSR offsets into removed
    std::vector<int> removed;          ///< neighbours that the next coarser level dropped
  };

  static IndexRange range(const std::vector<int>& begin, const std::vector<int>& ids, int i) {
    return IndexRange(ids.data() + begin[i], ids.data() + begin[i + 1]);
  }
  void buildHierarchy();
  void buildDirectionTable();
  /// Start vertex for direction d from the direction table (-1 if none).
  int tableStart(const Eigen::Vector3d& d_P) const;
  int climbLevel(const HierarchyLevel& level, const Eigen::Vector3d& d_P, int local_start, SupportStats* stats) const;
  int descendLevel(const HierarchyLevel& level, const Eigen::Vector3d& d_P, int local, SupportStats* stats) const;

  bool flat_ = false;
  Eigen::Vector3d p_PL_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> vertices_L_;  ///< what the queries use
  std::vector<Eigen::Vector3d> vertices_P_;  ///< the input points, for the public accessors
  std::vector<Eigen::Vector3d> face_normals_P_;
  std::vector<double> face_offsets_L_;
  std::vector<int> face_vertex_begin_;
  std::vector<int> face_vertex_ids_;
  std::vector<int> face_edge_ids_;
  std::vector<Edge> edges_;
  std::vector<int> vertex_adj_begin_;
  std::vector<int> vertex_neighbors_;
  std::vector<int> vertex_edges_;
  std::vector<int> vertex_face_begin_;
  std::vector<int> vertex_face_ids_;
  Eigen::Vector3d centroid_L_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d centroid_P_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;
  std::vector<HierarchyLevel> levels_;  ///< levels_[0] is the first coarsened level
  /// Direction table: 6 cube faces x table_k_ x table_k_ cells, each the
  /// support vertex of the cell's central direction.
  int table_k_ = 0;
  std::vector<int> table_;
  std::vector<int> removed_begin_;  ///< CSR: neighbours of each vertex that levels_[0] dropped
  std::vector<int> removed_;
};

}  // namespace mddual

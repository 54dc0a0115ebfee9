// ConvexPolytope and the result types of the queries, as read-only Python
// classes. Vectors come back as NumPy arrays (copies); statuses as strings.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.h"
#include "convert.h"
#include "mddual/distance.h"
#include "mddual/query.h"
#include "typed.h"

namespace mddual::python {
namespace {

py::tuple featureTuple(const Feature& f) {
  return py::make_tuple(toString(f.type), f.index);
}

std::string number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

py::array_t<double> vectorsArray(const std::vector<Eigen::Vector3d>& v) {
  py::array_t<double> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto w = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (py::ssize_t j = 0; j < 3; ++j) w(static_cast<py::ssize_t>(i), j) = v[i](j);
  }
  return out;
}

void bindPolytope(py::module_& m) {
  py::class_<ConvexPolytope>(m, "ConvexPolytope",
                             "A convex polytope: the convex hull of an (N, 3) array of points in its body frame. "
                             "Raises InvalidInputError (empty set, non-finite coordinate) or "
                             "DegenerateGeometryError (all points collinear or coincident).")
      .def(
          py::init([](const ArrayLikeArg& points) { return ConvexPolytope::fromPoints(pointsFrom(points, "points")); }),
          py::arg("points"))
      .def_property_readonly(
          "vertices", [](const ConvexPolytope& p) { return vectorsArray(p.vertices()); },
          "(V, 3) array: the hull's vertices in the body frame (input points)")
      .def_property_readonly("num_vertices", &ConvexPolytope::numVertices)
      .def_property_readonly("num_edges", &ConvexPolytope::numEdges)
      .def_property_readonly("num_faces", &ConvexPolytope::numFaces,
                             "number of faces (coplanar hull facets merged; a flat polygon has 2)")
      .def_property_readonly("is_flat", &ConvexPolytope::isFlat, "True when all vertices lie in one plane")
      .def_property_readonly("centroid", [](const ConvexPolytope& p) { return Eigen::Vector3d(p.centroid()); })
      .def_property_readonly("radius", &ConvexPolytope::radius, "largest distance from the centroid to a vertex")
      .def_property_readonly(
          "face_normals",
          [](const ConvexPolytope& p) {
            std::vector<Eigen::Vector3d> n(static_cast<std::size_t>(p.numFaces()));
            for (int f = 0; f < p.numFaces(); ++f) n[static_cast<std::size_t>(f)] = p.faceNormal(f);
            return vectorsArray(n);
          },
          "(F, 3) array of unit outward face normals n (the polytope lies in n . x <= h)")
      .def_property_readonly(
          "face_offsets",
          [](const ConvexPolytope& p) {
            std::vector<double> h(static_cast<std::size_t>(p.numFaces()));
            for (int f = 0; f < p.numFaces(); ++f) h[static_cast<std::size_t>(f)] = p.faceOffset(f);
            return py::array_t<double>(static_cast<py::ssize_t>(h.size()), h.data());
          },
          "(F,) array of face offsets h")
      .def_property_readonly(
          "faces",
          [](const ConvexPolytope& p) {
            std::vector<std::vector<int>> faces(static_cast<std::size_t>(p.numFaces()));
            for (int f = 0; f < p.numFaces(); ++f) {
              for (int v : p.faceVertices(f)) faces[static_cast<std::size_t>(f)].push_back(v);
            }
            return faces;
          },
          "list of faces, each the list of its vertex indices, counter-clockwise seen from outside")
      .def("__repr__", [](const ConvexPolytope& p) {
        return "ConvexPolytope(vertices=" + std::to_string(p.numVertices()) +
               ", faces=" + std::to_string(p.numFaces()) + (p.isFlat() ? ", flat" : "") + ")";
      });
}

void bindResults(py::module_& m) {
  py::class_<MddResult>(m, "MddResult",
                        "Result of mdd(): status ('separated', 'touching', 'penetrating', 'no_contact'), the signed "
                        "directional distance, the interval [t_lo, t_hi] where the line meets A - B (NaN where not "
                        "computed) and the contact (normal from A toward B, point on A).")
      .def_property_readonly("status", [](const MddResult& r) { return toString(r.status); })
      .def_readonly("distance", &MddResult::distance)
      .def_readonly("t_lo", &MddResult::t_lo)
      .def_readonly("t_hi", &MddResult::t_hi)
      .def_property_readonly(
          "t", [](const MddResult& r) { return r.contact.t; }, "t of the reported contact")
      .def_property_readonly("normal", [](const MddResult& r) { return Eigen::Vector3d(r.contact.normal_W); })
      .def_property_readonly("point", [](const MddResult& r) { return Eigen::Vector3d(r.contact.point_W); })
      .def_property_readonly("feature_a", [](const MddResult& r) { return featureTuple(r.contact.feature_a); })
      .def_property_readonly("feature_b", [](const MddResult& r) { return featureTuple(r.contact.feature_b); })
      .def("__repr__", [](const MddResult& r) {
        return std::string("MddResult(status='") + toString(r.status) + "', distance=" + number(r.distance) +
               ", t_lo=" + number(r.t_lo) + ", t_hi=" + number(r.t_hi) + ")";
      });

  py::class_<ToiResult>(m, "ToiResult",
                        "Result of toi(): status ('hit', 'in_contact', 'never'), toi (> 0 for 'hit', 0 for "
                        "'in_contact', inf for 'never') and, for 'hit', the contact.")
      .def_property_readonly("status", [](const ToiResult& r) { return toString(r.status); })
      .def_readonly("toi", &ToiResult::toi)
      .def_readonly("toi_exact", &ToiResult::toi_exact)
      .def_property_readonly("normal", [](const ToiResult& r) { return Eigen::Vector3d(r.contact.normal_W); })
      .def_property_readonly("point", [](const ToiResult& r) { return Eigen::Vector3d(r.contact.point_W); })
      .def("__repr__", [](const ToiResult& r) {
        return std::string("ToiResult(status='") + toString(r.status) + "', toi=" + number(r.toi) + ")";
      });

  py::class_<IntersectResult>(m, "IntersectResult",
                              "Result of intersect(): status ('separated', 'touching', 'penetrating'), intersecting "
                              "(status != 'separated') and, when separated, a unit normal n with max over A of "
                              "n . x < min over B of n . x.")
      .def_property_readonly("status", [](const IntersectResult& r) { return toString(r.status); })
      .def_readonly("intersecting", &IntersectResult::intersecting)
      .def_property_readonly("separating_normal",
                             [](const IntersectResult& r) { return Eigen::Vector3d(r.separating_normal_W); })
      .def("__bool__", [](const IntersectResult& r) { return r.intersecting; })
      .def("__repr__", [](const IntersectResult& r) {
        return std::string("IntersectResult(status='") + toString(r.status) + "')";
      });

  py::class_<PenetrationResult>(m, "PenetrationResult",
                                "Result of penetration_depth(): status ('separated', 'touching', 'penetrating'), "
                                "depth (0 unless penetrating), translation = depth * normal (moving B by it "
                                "separates the interiors) and the unit normal from A toward B (NaN unless "
                                "penetrating).")
      .def_property_readonly("status", [](const PenetrationResult& r) { return toString(r.status); })
      .def_readonly("depth", &PenetrationResult::depth)
      .def_property_readonly("translation", [](const PenetrationResult& r) { return Eigen::Vector3d(r.translation_W); })
      .def_property_readonly("normal", [](const PenetrationResult& r) { return Eigen::Vector3d(r.normal_W); })
      .def_property_readonly("feature_a", [](const PenetrationResult& r) { return featureTuple(r.feature_a); })
      .def_property_readonly("feature_b", [](const PenetrationResult& r) { return featureTuple(r.feature_b); })
      .def_readonly("delta", &PenetrationResult::delta)
      .def("__repr__", [](const PenetrationResult& r) {
        return std::string("PenetrationResult(status='") + toString(r.status) + "', depth=" + number(r.depth) + ")";
      });

  py::class_<DistanceResult>(m, "DistanceResult",
                             "Result of distance(): status ('separated', 'touching', 'penetrating'), distance "
                             "(signed: minus the penetration depth when penetrating), the witness points point_a "
                             "and point_b (world frame) and the unit normal from A toward B.")
      .def_property_readonly("status", [](const DistanceResult& r) { return toString(r.status); })
      .def_readonly("distance", &DistanceResult::distance)
      .def_property_readonly("point_a", [](const DistanceResult& r) { return Eigen::Vector3d(r.p_WA); })
      .def_property_readonly("point_b", [](const DistanceResult& r) { return Eigen::Vector3d(r.p_WB); })
      .def_property_readonly("normal", [](const DistanceResult& r) { return Eigen::Vector3d(r.normal_W); })
      .def("__repr__", [](const DistanceResult& r) {
        return std::string("DistanceResult(status='") + toString(r.status) + "', distance=" + number(r.distance) + ")";
      });

  py::class_<WidthResult>(m, "WidthResult",
                          "Result of width(): the smallest distance between two parallel planes enclosing the "
                          "polytope, and a unit normal of those planes (world frame).")
      .def_readonly("width", &WidthResult::width)
      .def_property_readonly("direction", [](const WidthResult& r) { return Eigen::Vector3d(r.direction_W); })
      .def_readonly("delta", &WidthResult::delta)
      .def("__repr__", [](const WidthResult& r) { return std::string("WidthResult(width=") + number(r.width) + ")"; });
}

}  // namespace

void bindTypes(py::module_& m) {
  bindPolytope(m);
  bindResults(m);
}

}  // namespace mddual::python

// Helpers shared by the loaders' translation units (not installed).
#pragma once

#include <Eigen/Geometry>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mddual/constants.h"  // kPi
#include "mddual/error.h"
#include "mddual/scene/loaders.h"
#include "mddual/scene/scene.h"

namespace mddual::scene::detail {

/// `s` in lower case (ASCII).
inline std::string lowerCase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// "'text'", control bytes shown as '?' (clipForMessage, not cut: it also
/// quotes the file names in piece names).
inline std::string quote(const std::string& text) {
  return "'" + clipForMessage(text, std::string::npos) + "'";
}

/// The path as the user gave it, for messages.
inline std::string display(const std::filesystem::path& p) {
  return p.string();
}

/// Throws SceneError unless `file` is an existing regular file.
void requireFile(const std::filesystem::path& file);

/// Throws SceneError(what + ": " + reason) unless `tolerance` is a
/// mesh_convex_tolerance in [0, kMaxMeshConvexTolerance].
void requireMeshConvexTolerance(double tolerance, const std::string& what);

/// Throws SceneError(what + ": " + reason) unless `tolerance` is finite and > 0.
void requirePositiveTolerance(double tolerance, const std::string& what);

/// The triangles and vertices of a mesh file, as OMPL.app reads them (see
/// loaders.h), in the file's frame.
struct MeshData {
  std::vector<Eigen::Vector3d> vertices;   ///< every vertex of every referenced mesh
  std::vector<Eigen::Vector3d> triangles;  ///< three corners per triangle
};

/// Reads a mesh file with assimp. Throws SceneError naming the file (and the
/// vertex, for a coordinate that is NaN or overflows assimp's 32-bit floats).
MeshData readMesh(const std::filesystem::path& file);

/// The first line of an error message, cut to a couple of hundred characters
/// (qhull's reports run to kilobytes and must not reach the user raw).
std::string briefReason(const std::string& message);

/// Builds a hull (ConvexPolytope::fromPoints; tests pass one that fails).
using HullBuilder = ConvexPolytope (*)(const std::vector<Eigen::Vector3d>&);

/// How the triangles of a mesh connect (meshTopology).
struct MeshTopology {
  bool closed = false;    ///< every edge shared by exactly two triangles
  bool oriented = false;  ///< closed, and every edge used once in each direction
};

/// The topology of triangles (three corners each): corners are the same
/// vertex when their positions are equal; a triangle with two equal corners
/// is left out (it has no proper edges). No triangles: not closed.
MeshTopology meshTopology(const std::vector<Eigen::Vector3d>& corners);

/// Why checkConvexity said what it said.
enum class ConvexityVerdict : std::uint8_t {
  kConvex,      ///< the triangles bound their hull within plane_tol
  kWitness,     ///< a triangle has mesh points too far on both sides of its plane (no hull built)
  kHullFailed,  ///< the hull could not be built (hull_error says why)
  kOffHull,     ///< a triangle is not within plane_tol of a supporting plane of the hull
  kUncovered,   ///< the triangles do not cover the hull's boundary (volume and area tests)
};

/// The outcome of checkConvexity.
struct ConvexityCheck {
  bool convex = false;  ///< the triangles are the boundary of their hull, within plane_tol
  ConvexityVerdict verdict = ConvexityVerdict::kWitness;
  int triangle = -1;       ///< kWitness, kOffHull: the triangle (index in `tri` / 3)
  bool has_hull = false;   ///< `hull` was built
  ConvexPolytope hull;     ///< the hull of the triangles' corners (when has_hull)
  std::string hull_error;  ///< why the hull could not be built (briefReason), else empty
};

/// Decides whether the triangles (three corners each, none degenerate) are
/// the boundary of a convex body, within plane_tol (the test of meshPieces,
/// loaders.h): first a bounded search for a triangle with corners beyond
/// both sides of its plane (then the mesh is not convex and no hull is
/// built), then `build_hull` and a comparison of the triangles with the hull:
/// each within plane_tol of a supporting plane, and covering it (by the
/// enclosed volume when `oriented`, the mesh being closed and consistently
/// oriented, or else by area). A HullError, NumericalError or
/// DegenerateGeometryError from build_hull never escapes: the mesh is then
/// reported not convex, with the reason in hull_error.
ConvexityCheck checkConvexity(const std::vector<Eigen::Vector3d>& tri, double plane_tol, HullBuilder build_hull,
                              bool oriented = false);

/// The pieces of mesh data already read (meshPiecesWithOrigin after
/// readMesh; the in-memory builders of builders.h): every check and the
/// convexity handling of meshPieces. `file` only names the source in messages
/// (a file, or a label for in-memory arrays). The data's vertices must be
/// finite (readMesh and the builders check them).
std::vector<Piece> meshDataPieces(const MeshData& data, const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                  const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                  const std::string& origin_prefix, MeshInfo* info);

/// meshPieces with the pieces' origins prefixed by `origin_prefix`
/// ("<prefix>: triangle 3").
std::vector<Piece> meshPiecesWithOrigin(const std::filesystem::path& file, const Eigen::Vector3d& scale,
                                        const Eigen::Isometry3d& X_OM, const LoadOptions& options,
                                        const std::string& origin_prefix, MeshInfo* info);

/// The collision pieces of a URDF file in its root link's frame; `robot_name`
/// receives the URDF's robot name; `warnings` (if not null) receives the
/// meshes' load warnings, each prefixed with its link and collision element;
/// `counts` (if not null) has the meshes added. Throws SceneError naming the
/// file, link and collision element.
std::vector<Piece> urdfPieces(const std::filesystem::path& file, const LoadOptions& options, std::string* robot_name,
                              std::vector<std::string>* warnings, MeshCounts* counts);

/// True when `file`'s extension is .urdf (any case).
bool isUrdf(const std::filesystem::path& file);

/// True for mesh formats that are XML (COLLADA .dae, any case), which
/// readMesh checks with requireShallowXml before assimp parses them.
bool isXmlMesh(const std::filesystem::path& file);

/// Deepest element nesting an XML file may have. XML parsers (urdfdom's
/// TinyXML, assimp's COLLADA reader) recurse once per level, so a file nested
/// tens of thousands deep overflows their stack; real URDF and COLLADA files
/// nest about ten deep.
constexpr int kMaxXmlElementDepth = 256;

/// Element nesting found by xmlElementDepth.
struct XmlDepth {
  int depth = 0;  ///< deepest nesting seen (the scan stops once it exceeds the limit)
  int line = 0;   ///< line (from 1) of the start tag that reached it; 0 without elements
};

/// The element nesting of XML text, by a linear scan that skips comments,
/// CDATA sections, processing instructions, declarations (with an internal
/// subset) and quoted attribute values; stops at the first start tag deeper
/// than `limit`. Not a validator: malformed text is left to the parser.
XmlDepth xmlElementDepth(std::string_view text, int limit = kMaxXmlElementDepth);

/// Throws SceneError (naming the file, the depth and the line) when `file`
/// nests its elements deeper than kMaxXmlElementDepth, or cannot be read;
/// returns the file's text otherwise.
std::string requireShallowXml(const std::filesystem::path& file);

}  // namespace mddual::scene::detail

// Python arguments and results that the bindings take or give as plain
// Python objects, but whose signatures (help(), and through them the type
// stubs that scripts/gen_stubs.py writes) name their Python types.
//
// Typed<Hint> is a py::object that pybind11 accepts from any Python object
// (the binding converts it, and convert.h raises TypeError or ValueError
// naming the argument) and names Hint::text in signatures, as pybind11 names
// its own casters' types ("numpy.ndarray[numpy.float64[3, 1]]"). The names of
// the module's classes are spelled "mddual.X", as pybind11 spells them; the
// stub generator drops the prefix. A result of type Typed<Hint> is returned
// as it is.
#pragma once

#include <pybind11/pybind11.h>

#include <utility>

namespace mddual::python {

namespace py = pybind11;

/// A Python object named Hint::text in signatures (see the file comment).
template <class Hint>
class Typed : public py::object {
 public:
  Typed() = default;
  // Implicit, as pybind11's own object types: from any object or array.
  // NOLINTNEXTLINE(google-explicit-constructor)
  Typed(const py::object& o) : py::object(o) {}
  // NOLINTNEXTLINE(google-explicit-constructor)
  Typed(py::object&& o) : py::object(std::move(o)) {}
  Typed(py::handle h, borrowed_t b) : py::object(h, b) {}
  Typed(py::handle h, stolen_t s) : py::object(h, s) {}
  /// pybind11's check when it loads an argument: any object.
  static bool check_(py::handle h) { return h.ptr() != nullptr; }
};

namespace hint {
// Arguments.
struct ArrayLike {
  static constexpr char text[] = "numpy.typing.ArrayLike";
};
struct ArrayLikeOrNone {
  static constexpr char text[] = "numpy.typing.ArrayLike | None";
};
struct Link {
  static constexpr char text[] = "str | int";
};
struct Links {
  static constexpr char text[] = "Sequence[str | int] | None";
};
struct Polytopes {
  static constexpr char text[] = "Iterable[mddual.ConvexPolytope] | None";
};
struct Allowed {
  static constexpr char text[] = "mddual.AllowedCollisions | mddual.Srdf | None";
};
struct RobotOrPath {
  static constexpr char text[] = "mddual.RobotModel | str | os.PathLike[str]";
};
struct SrdfOrPath {
  static constexpr char text[] = "mddual.Srdf | str | os.PathLike[str]";
};
struct ProblemFiles {
  static constexpr char text[] = "mddual.ArmProblemFiles | tuple[str | os.PathLike[str], str | os.PathLike[str]]";
};
struct CastSegments {
  static constexpr char text[] = "Literal['resolution', 'whole_edge']";
};
// Results.
struct BoolOrArray {
  static constexpr char text[] = "bool | numpy.typing.NDArray[numpy.bool_]";
};
struct FloatOrArray {
  static constexpr char text[] = "float | numpy.typing.NDArray[numpy.float64]";
};
struct FloatArray {
  static constexpr char text[] = "numpy.typing.NDArray[numpy.float64]";
};
struct ArrayDict {
  static constexpr char text[] = "dict[str, numpy.typing.NDArray[Any]]";
};
struct EdgeResults {
  static constexpr char text[] =
      "tuple[bool, float] | tuple[numpy.typing.NDArray[numpy.bool_], numpy.typing.NDArray[numpy.float64]]";
};
struct ArmContact {
  static constexpr char text[] = "dict[str, str | int | None] | None";
};
}  // namespace hint

/// An array of numbers in any form numpy.asarray takes (convert.h).
using ArrayLikeArg = Typed<hint::ArrayLike>;
/// An array of numbers, or None (a pose: the identity).
using ArrayLikeOrNoneArg = Typed<hint::ArrayLikeOrNone>;
/// A link by name or index (linkIndexFrom).
using LinkArg = Typed<hint::Link>;
/// Links by name or index, or None for all (linkSelection).
using LinksArg = Typed<hint::Links>;
/// ConvexPolytope pieces, or None for none.
using PolytopesArg = Typed<hint::Polytopes>;
/// An AllowedCollisions, an Srdf or None.
using AllowedArg = Typed<hint::Allowed>;
using RobotOrPathArg = Typed<hint::RobotOrPath>;
using SrdfOrPathArg = Typed<hint::SrdfOrPath>;
/// An ArmProblemFiles or a (scene, request) pair of paths.
using ProblemFilesArg = Typed<hint::ProblemFiles>;
/// The hull-cast checks' segments (a str).
using CastSegmentsArg = Typed<hint::CastSegments>;

/// bool for one item, a bool array for a batch.
using BoolOrArray = Typed<hint::BoolOrArray>;
/// float for one item, a float64 array for a batch.
using FloatOrArray = Typed<hint::FloatOrArray>;
using FloatArray = Typed<hint::FloatArray>;
/// {name: array}.
using ArrayDict = Typed<hint::ArrayDict>;
/// (collides, fraction): a bool and a float for one edge, arrays for a batch.
using EdgeResults = Typed<hint::EdgeResults>;
/// ArmScene.contact's dict, or None.
using ArmContactResult = Typed<hint::ArmContact>;

}  // namespace mddual::python

namespace pybind11::detail {
template <class Hint>
struct handle_type_name<mddual::python::Typed<Hint>> {
  static constexpr auto name = const_name(Hint::text);
};
}  // namespace pybind11::detail

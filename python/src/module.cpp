// The mddual Python module: exact collision queries between convex polytopes
// given as NumPy arrays. See python/README.md.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "convert.h"

PYBIND11_MODULE(mddual, m) {
  namespace mp = mddual::python;
  m.doc() =
      "Exact collision queries between convex polytopes (MDD-DUAL): signed minimum directional distance, time of "
      "impact, intersection, penetration depth and width. Poses are 4x4 arrays (None for the identity); A is "
      "fixed, B moves.";
  m.attr("__version__") = MDDUAL_VERSION_STRING;
  mp::initConversions();
  mp::bindErrors(m);
  mp::bindTypes(m);
  mp::bindQueries(m);
  mp::bindBatch(m);
#ifdef MDDUAL_PYTHON_HAS_PLANNING
  mp::bindScene(m);
  mp::bindRobot(m);
  mp::bindArms(m);
#endif
#ifdef MDDUAL_PYTHON_HAS_HULL_CAST
  mp::bindHullCast(m);
#endif
}

// The library's exception types as Python classes:
//
//   mddual.Error(Exception)
//   ├── mddual.InvalidInputError(Error, ValueError)
//   │   └── mddual.DegenerateGeometryError(InvalidInputError)
//   ├── mddual.HullError(Error, RuntimeError)
//   └── mddual.NumericalError(Error, RuntimeError)
//
// Each carries the C++ exception's message unchanged.
#include "mddual/error.h"

#include "bindings.h"

namespace mddual::python {
namespace {

/// The Python classes, created once at import and owned by the module (the
/// module's attributes keep them alive for the interpreter's lifetime).
struct ErrorClasses {
  PyObject* error = nullptr;
  PyObject* invalid_input = nullptr;
  PyObject* degenerate = nullptr;
  PyObject* hull = nullptr;
  PyObject* numerical = nullptr;
};

ErrorClasses& errorClasses() {
  static ErrorClasses classes;
  return classes;
}

PyObject* addErrorClass(py::module_& m, const char* name, const py::object& bases, const char* doc) {
  const std::string qualified = std::string("mddual.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (cls == nullptr) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(cls));
  return cls;  // the new reference is kept for the translator
}

}  // namespace

void bindErrors(py::module_& m) {
  ErrorClasses& c = errorClasses();
  c.error = addErrorClass(m, "Error", py::reinterpret_borrow<py::object>(PyExc_Exception),
                          "Base of every error the mddual library raises.");
  const auto error = py::reinterpret_borrow<py::object>(c.error);
  c.invalid_input =
      addErrorClass(m, "InvalidInputError", py::make_tuple(error, py::handle(PyExc_ValueError)),
                    "The caller passed something unusable: non-finite coordinates, too few points, a zero "
                    "direction, a pose that is not a rigid transform.");
  c.degenerate = addErrorClass(m, "DegenerateGeometryError", py::reinterpret_borrow<py::object>(c.invalid_input),
                               "The points are well formed but degenerate (all collinear or coincident).");
  c.hull = addErrorClass(m, "HullError", py::make_tuple(error, py::handle(PyExc_RuntimeError)),
                         "The convex hull kernel (qhull) failed on the input.");
  c.numerical = addErrorClass(m, "NumericalError", py::make_tuple(error, py::handle(PyExc_RuntimeError)),
                              "An internal consistency check failed; the message carries the query so that it "
                              "can be reproduced.");

  py::register_exception_translator([](std::exception_ptr p) {
    const ErrorClasses& k = errorClasses();
    try {
      if (p) std::rethrow_exception(p);
    } catch (const DegenerateGeometryError& e) {
      PyErr_SetString(k.degenerate, e.what());
    } catch (const InvalidInputError& e) {
      PyErr_SetString(k.invalid_input, e.what());
    } catch (const HullError& e) {
      PyErr_SetString(k.hull, e.what());
    } catch (const NumericalError& e) {
      PyErr_SetString(k.numerical, e.what());
    } catch (const Error& e) {
      PyErr_SetString(k.error, e.what());
    }
  });
}

}  // namespace mddual::python

#include "convert.h"

#include <sstream>

#include "mddual/error.h"

namespace mddual::python {

namespace {

/// numpy.asarray and the float64 dtype, set by initConversions() when the
/// module is imported (the GIL held; a function-local static would run
/// Python under C++'s one-time lock) and kept to the process's exit.
const py::object* g_asarray = nullptr;
const py::object* g_float64 = nullptr;

/// A Python error from a conversion: MemoryError, KeyboardInterrupt and the
/// like pass through; only a value NumPy cannot read (TypeError, ValueError,
/// OverflowError) is the caller's "not convertible".
bool unreadable(const py::error_already_set& e) {
  return e.matches(PyExc_TypeError) || e.matches(PyExc_ValueError) || e.matches(PyExc_OverflowError);
}

}  // namespace

void initConversions() {
  g_asarray = new py::object(py::module_::import("numpy").attr("asarray"));
  g_float64 = new py::object(py::module_::import("numpy").attr("float64"));
}

DoubleArray toDoubleArray(const py::handle& obj, const char* name, const char* expected) {
  if (obj.is_none()) {
    throw py::type_error(std::string(name) + ": expected " + expected + ", got None");
  }
  if (DoubleArray::check_(obj)) return py::reinterpret_borrow<DoubleArray>(obj);  // float64, C order already
  // NumPy's own conversions, so that a MemoryError stays one (pybind11's
  // cast reported it as "not convertible"), and a look at the values' kind
  // first: a cast to float64 took complex numbers (dropping the imaginary
  // part), dates and numeric strings. Object arrays (Fraction, Decimal,
  // integers beyond 64 bits) are converted by float() per element.
  const auto notConvertible = [&](const std::string& why) {
    const std::string type = py::str(py::type::of(obj).attr("__name__"));
    return py::type_error(std::string(name) + ": expected " + expected + ", got a " + type + why);
  };
  py::object converted;
  try {
    converted = py::isinstance<py::array>(obj) ? py::reinterpret_borrow<py::object>(obj) : (*g_asarray)(obj);
  } catch (py::error_already_set& e) {
    if (!unreadable(e)) throw;
    throw notConvertible(" that is not convertible to an array of float64");
  }
  const char kind = py::reinterpret_borrow<py::array>(converted).dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f' && kind != 'O') {
    const std::string dtype = py::str(py::reinterpret_borrow<py::array>(converted).dtype());
    throw notConvertible(" of dtype " + dtype + " (real numbers only: no complex, date, string or bytes values)");
  }
  try {
    converted = (*g_asarray)(converted, py::arg("dtype") = *g_float64, py::arg("order") = "C");
  } catch (py::error_already_set& e) {
    if (!unreadable(e)) throw;
    throw notConvertible(" that is not convertible to an array of float64");
  }
  return py::reinterpret_borrow<DoubleArray>(converted);
}

std::string shapeText(const py::array& a) {
  std::ostringstream out;
  out << '(';
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    out << (i > 0 ? ", " : "") << a.shape(i);
  }
  out << (a.ndim() == 1 ? ",)" : ")");
  return out.str();
}

std::vector<Eigen::Vector3d> pointsFrom(const py::handle& obj, const char* name) {
  const char* expected = "an (N, 3) array of points";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  const auto v = a.unchecked<2>();
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    points[static_cast<std::size_t>(i)] = Eigen::Vector3d(v(i, 0), v(i, 1), v(i, 2));
  }
  return points;
}

namespace {

/// The pose stored at `m` (16 doubles, row-major); InvalidInputError when the
/// last row is not [0, 0, 0, 1].
Eigen::Isometry3d poseFromRowMajor(const double* m, const std::string& name) {
  if (!(m[12] == 0.0 && m[13] == 0.0 && m[14] == 0.0 && m[15] == 1.0)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << name << ": the last row of a pose must be [0, 0, 0, 1], got [" << m[12] << ", " << m[13] << ", " << m[14]
        << ", " << m[15] << "]";
    throw InvalidInputError(msg.str());
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) X.matrix()(r, c) = m[4 * r + c];
  }
  return X;
}

}  // namespace

Eigen::Isometry3d poseFrom(const py::handle& obj, const char* name) {
  if (obj.is_none()) return Eigen::Isometry3d::Identity();
  const char* expected = "a 4x4 pose (or None for the identity)";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  return poseFromRowMajor(a.data(), name);
}

Eigen::Vector3d vectorFrom(const py::handle& obj, const char* name) {
  const char* expected = "a 3-vector";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  if (a.ndim() != 1 || a.shape(0) != 3) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  return Eigen::Vector3d(a.at(0), a.at(1), a.at(2));
}

PoseBatch poseBatchFrom(const py::handle& obj, const char* name) {
  PoseBatch batch;
  if (obj.is_none()) {
    batch.poses.push_back(Eigen::Isometry3d::Identity());
    return batch;
  }
  const char* expected = "a (K, 4, 4) array of poses, one 4x4 pose or None";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  if (a.ndim() == 2 && a.shape(0) == 4 && a.shape(1) == 4) {
    batch.poses.push_back(poseFromRowMajor(a.data(), name));
    return batch;
  }
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  batch.batched = true;
  batch.poses.reserve(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) {
    batch.poses.push_back(poseFromRowMajor(a.data(k, 0, 0), std::string(name) + "[" + std::to_string(k) + "]"));
  }
  return batch;
}

VectorBatch vectorBatchFrom(const py::handle& obj, const char* name) {
  const char* expected = "a (K, 3) array of vectors or one 3-vector";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  VectorBatch batch;
  if (a.ndim() == 1 && a.shape(0) == 3) {
    batch.vectors.emplace_back(a.at(0), a.at(1), a.at(2));
    return batch;
  }
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  batch.batched = true;
  const auto v = a.unchecked<2>();
  batch.vectors.reserve(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) batch.vectors.emplace_back(v(k, 0), v(k, 1), v(k, 2));
  return batch;
}

ScalarBatch scalarBatchFrom(const py::handle& obj, const char* name) {
  const char* expected = "a number or a (K,) array of numbers";
  const DoubleArray a = toDoubleArray(obj, name, expected);
  ScalarBatch batch;
  if (a.ndim() == 0) {
    batch.values.push_back(*a.data());
    return batch;
  }
  if (a.ndim() != 1) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  batch.batched = true;
  batch.values.assign(a.data(), a.data() + a.shape(0));
  return batch;
}

StateBatch stateBatchFrom(const py::handle& obj, const char* name, int d, const char* noun) {
  const std::string n = std::string(noun);
  const std::string expected =
      "a (K, " + std::to_string(d) + ") array of " + n + "s or one " + n + " of " + std::to_string(d) + " numbers";
  const DoubleArray a = toDoubleArray(obj, name, expected.c_str());
  StateBatch batch;
  if (a.ndim() == 1 && a.shape(0) == d) {
    batch.values.assign(a.data(), a.data() + d);
    return batch;
  }
  if (a.ndim() != 2 || a.shape(1) != d) {
    throw py::value_error(std::string(name) + ": expected " + expected + ", got shape " + shapeText(a));
  }
  batch.batched = true;
  batch.count = static_cast<std::size_t>(a.shape(0));
  batch.values.assign(a.data(), a.data() + a.size());
  return batch;
}

std::string itemName(const char* name, std::size_t k, bool batched) {
  return batched ? std::string(name) + "[" + std::to_string(k) + "]" : std::string(name);
}

void BatchSize::add(std::size_t size, bool batched, const char* name) {
  if (!batched) return;
  if (first_ != nullptr && size != size_) {
    throw py::value_error(std::string("batch sizes differ: ") + first_ + " has " + std::to_string(size_) +
                          " entries, " + name + " has " + std::to_string(size));
  }
  if (first_ == nullptr) {
    first_ = name;
    size_ = size;
  }
}

std::size_t batchSizeOf(const StateBatch& a, const char* a_name, const StateBatch& b, const char* b_name) {
  BatchSize size;
  size.add(a.count, a.batched, a_name);
  size.add(b.count, b.batched, b_name);
  return size.size();
}

}  // namespace mddual::python

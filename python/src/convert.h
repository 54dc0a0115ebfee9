// Conversions between NumPy arrays and the library's Eigen types, for the
// Python module. Every conversion names the argument it failed on: a value
// that is not an array of numbers is a TypeError, an array of the wrong
// shape a ValueError, and a pose whose last row is not [0, 0, 0, 1] the
// library's own InvalidInputError (the library checks the rest of a pose).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mddual::python {

namespace py = pybind11;

/// A C-contiguous float64 view of `obj` (converted when needed).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `obj` as a float64 array; TypeError naming `name` when it cannot be one.
DoubleArray toDoubleArray(const py::handle& obj, const char* name, const char* expected);
/// Looks up the NumPy functions toDoubleArray uses; called once when the
/// module is imported.
void initConversions();

/// "(4, 4)" for an array of shape 4 x 4.
std::string shapeText(const py::array& a);

/// An (N, 3) array of points.
std::vector<Eigen::Vector3d> pointsFrom(const py::handle& obj, const char* name);

/// A 4x4 homogeneous rigid transform, or None for the identity.
Eigen::Isometry3d poseFrom(const py::handle& obj, const char* name);

/// A 3-vector.
Eigen::Vector3d vectorFrom(const py::handle& obj, const char* name);

/// Poses for a batch: None, (4, 4) (one pose for every query) or (K, 4, 4).
struct PoseBatch {
  std::vector<Eigen::Isometry3d> poses;
  bool batched = false;  ///< one pose per query (else poses has one entry)
  const Eigen::Isometry3d& operator[](std::size_t k) const { return batched ? poses[k] : poses[0]; }
};
PoseBatch poseBatchFrom(const py::handle& obj, const char* name);

/// Vectors for a batch: (3,) (one for every query) or (K, 3).
struct VectorBatch {
  std::vector<Eigen::Vector3d> vectors;
  bool batched = false;
  const Eigen::Vector3d& operator[](std::size_t k) const { return batched ? vectors[k] : vectors[0]; }
};
VectorBatch vectorBatchFrom(const py::handle& obj, const char* name);

/// Scalars for a batch: a number (one for every query) or a (K,) array.
struct ScalarBatch {
  std::vector<double> values;
  bool batched = false;
  double operator[](std::size_t k) const { return batched ? values[k] : values[0]; }
};
ScalarBatch scalarBatchFrom(const py::handle& obj, const char* name);

/// Rows of d numbers for a batch: (d,) (one for every query) or (K, d),
/// flattened. ValueError naming `name` for another shape, the message
/// calling a row a `noun` ("a (K, 3) array of states or one state of 3
/// numbers").
struct StateBatch {
  std::vector<double> values;
  std::size_t count = 1;
  bool batched = false;
  const double* row(std::size_t k, int d) const {
    return values.data() + (batched ? k * static_cast<std::size_t>(d) : 0);
  }
};
StateBatch stateBatchFrom(const py::handle& obj, const char* name, int d, const char* noun);

/// "Q[3]" for row 3 of a batch, "Q" for a single row.
std::string itemName(const char* name, std::size_t k, bool batched);

/// The common batch size K of batched arguments (ValueError naming the two
/// arguments that disagree); 1 when none is batched.
class BatchSize {
 public:
  void add(std::size_t size, bool batched, const char* name);
  std::size_t size() const { return size_; }

 private:
  std::size_t size_ = 1;
  const char* first_ = nullptr;
};

/// The common size of two batches of rows (BatchSize over both).
std::size_t batchSizeOf(const StateBatch& a, const char* a_name, const StateBatch& b, const char* b_name);

}  // namespace mddual::python

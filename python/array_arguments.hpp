// numpy arrays in: each checked for its kind and shape with a message naming the argument, then
// viewed as the library's column-major Eigen types (without a copy when the array is already
// Fortran-ordered float64 / int32, converted once otherwise).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace posekit::python {

/// An n x 3 array of vertex coordinates, held while the library reads it.
class VerticesArgument {
 public:
  VerticesArgument(const pybind11::handle& array, const std::string& name);
  Eigen::Map<const Eigen::MatrixX3d> matrix() const;

 private:
  pybind11::array_t<double, pybind11::array::f_style | pybind11::array::forcecast> array_;
};

/// An m x 3 array of zero-based vertex indices.
class FacesArgument {
 public:
  FacesArgument(const pybind11::handle& array, const std::string& name);
  Eigen::Map<const Eigen::MatrixX3i> matrix() const;

 private:
  pybind11::array_t<int, pybind11::array::f_style | pybind11::array::forcecast> array_;
};

/// Each item of a sequence of n x 3 arrays, copied into the library's matrices.
std::vector<Eigen::MatrixX3d> vertices_list(const pybind11::handle& sequence, const std::string& name);

}  // namespace posekit::python

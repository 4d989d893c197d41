#include "array_arguments.hpp"

#include <posekit/error.hpp>

namespace posekit::python {
namespace py = pybind11;
namespace {

// The array as given (no conversion yet), or a ValueError naming the argument.
py::array as_array(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::array>(value)) {
    // Lists and other sequences are accepted as numpy would read them.
    try {
      return py::array::ensure(value);
    } catch (const py::error_already_set&) {
    }
    throw ArgumentError(name + " must be a numpy array, got " + std::string(py::str(value.get_type().attr("__name__"))));
  }
  return py::reinterpret_borrow<py::array>(value);
}

void check_shape(const py::array& array, const std::string& name, const char* rows) {
  if (array.ndim() != 2 || array.shape(1) != 3) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d) shape += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
    throw ArgumentError(name + " must have shape (" + rows + ", 3), got " + shape + (array.ndim() == 1 ? ",)" : ")"));
  }
}

}  // namespace

VerticesArgument::VerticesArgument(const py::handle& value, const std::string& name) {
  const py::array array = as_array(value, name);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw ArgumentError(name + " must hold floating-point coordinates, got dtype " + std::string(py::str(array.dtype())));
  }
  check_shape(array, name, "n");
  array_ = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(array);
  if (!array_) throw ArgumentError(name + " cannot be read as float64 coordinates");
}

Eigen::Map<const Eigen::MatrixX3d> VerticesArgument::matrix() const {
  return {array_.data(), static_cast<Eigen::Index>(array_.shape(0)), 3};
}

FacesArgument::FacesArgument(const py::handle& value, const std::string& name) {
  const py::array array = as_array(value, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw ArgumentError(name + " must hold integer vertex indices, got dtype " + std::string(py::str(array.dtype())));
  }
  check_shape(array, name, "m");
  array_ = py::array_t<int, py::array::f_style | py::array::forcecast>::ensure(array);
  if (!array_) throw ArgumentError(name + " cannot be read as int32 vertex indices");
}

Eigen::Map<const Eigen::MatrixX3i> FacesArgument::matrix() const {
  return {array_.data(), static_cast<Eigen::Index>(array_.shape(0)), 3};
}

std::vector<Eigen::MatrixX3d> vertices_list(const py::handle& sequence, const std::string& name) {
  std::vector<Eigen::MatrixX3d> out;
  size_t index = 0;
  for (const py::handle item : sequence) {
    out.emplace_back(VerticesArgument(item, name + "[" + std::to_string(index) + "]").matrix());
    ++index;
  }
  return out;
}

}  // namespace posekit::python

// posekit._posekit: the library for Python. Arrays in and out are numpy's (vertices float64 n x 3,
// faces int32 m x 3); options are the command line's, as keyword arguments; reports are the
// command line's JSON, as dicts; long calls run without the GIL.
#include "array_arguments.hpp"
#include "keyword_options.hpp"

#include "backend_status_json.hpp"
#include "blend_common.hpp"
#include "correction_flags.hpp"
#include "correction_report_json.hpp"
#include "interpolation_flags.hpp"
#include "sequence_report_json.hpp"

#include <posekit/blended_deformation.hpp>
#include <posekit/correct.hpp>
#include <posekit/correct_sequence.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/partial_registration.hpp>
#include <posekit/self_intersections.hpp>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

namespace posekit::python {
namespace {

namespace py = pybind11;
using namespace pybind11::literals;

py::object to_python(const nlohmann::json& value) { return py::module_::import("json").attr("loads")(value.dump()); }

// The options of one correction from keyword arguments; `exclude` may be a file name, as on the
// command line, or a sequence of vertex indices.
CorrectionOptions correction_options_from(py::kwargs keywords, const std::string& function, int vertex_count,
                                          std::string& device) {
  std::vector<int> excluded;
  if (keywords.contains("exclude") && !py::isinstance<py::str>(keywords["exclude"])) {
    excluded = keywords["exclude"].cast<std::vector<int>>();
    PyDict_DelItemString(keywords.ptr(), "exclude");
  }
  CLI::App app{function, function};
  cli::CorrectionFlags flags;
  cli::add_correction_flags(&app, flags);
  parse_keywords(app, keywords);
  CorrectionOptions options = cli::correction_options(flags, vertex_count);
  if (!excluded.empty()) options.excluded_vertices = excluded;
  device = flags.device;
  return options;
}

// Calls a Python progress callback, if one was given, with (stage, fraction done), from a thread
// that does not hold the GIL.
class StageProgress {
 public:
  explicit StageProgress(const py::object& callback) : callback_(callback) {}
  void operator()(const std::string& stage, double fraction) const {
    if (callback_.is_none()) return;
    py::gil_scoped_acquire acquire;
    callback_(stage, fraction);
  }

 private:
  const py::object& callback_;
};

py::tuple read_mesh_python(const std::string& path) {
  Mesh mesh = read_mesh(path);
  return py::make_tuple(py::cast(std::move(mesh.vertices)), py::cast(std::move(mesh.faces)));
}

void write_mesh_python(const std::string& path, const py::object& v, const py::object& f) {
  const VerticesArgument vertices(v, "V");
  const FacesArgument faces(f, "F");
  write_mesh(path, Mesh{vertices.matrix(), faces.matrix()});
}

py::list devices_python() {
  py::list out;
  for (const BackendStatus& status : list_backends()) out.append(to_python(cli::backend_status_json(status)));
  return out;
}

py::dict check_python(const py::object& v, const py::object& f, const py::object& reference) {
  const VerticesArgument vertices(v, "V");
  const FacesArgument faces(f, "F");
  py::dict out;
  out["vertices"] = vertices.matrix().rows();
  out["faces"] = faces.matrix().rows();
  std::vector<int> intersecting;
  {
    py::gil_scoped_release release;
    intersecting = self_intersecting_faces(vertices.matrix(), faces.matrix());
  }
  out["self_intersecting_faces"] = intersecting.size();
  if (!reference.is_none()) {
    const VerticesArgument reference_vertices(reference, "reference");
    if (reference_vertices.matrix().rows() != vertices.matrix().rows()) {
      throw ArgumentError("reference has " + std::to_string(reference_vertices.matrix().rows()) + " vertices but V has " +
                          std::to_string(vertices.matrix().rows()));
    }
    std::vector<int> reference_faces;
    {
      py::gil_scoped_release release;
      reference_faces = self_intersecting_faces(reference_vertices.matrix(), faces.matrix());
    }
    out["reference_self_intersecting_faces"] = reference_faces.size();
    out["new_self_intersecting_faces"] = new_intersecting_faces(intersecting, reference_faces).size();
  }
  return out;
}

py::tuple correct_python(const py::object& reference, const py::object& target, const py::object& f,
                         const py::object& progress, const py::kwargs& keywords) {
  const VerticesArgument reference_vertices(reference, "V_ref");
  const VerticesArgument target_vertices(target, "V_target");
  const FacesArgument faces(f, "F");
  std::string device_name;
  const CorrectionOptions options = correction_options_from(keywords, "correct",
                                                            static_cast<int>(reference_vertices.matrix().rows()), device_name);
  CorrectionProgress callback;
  if (!progress.is_none()) {
    callback = [&progress](const std::string& stage, double fraction) {
      py::gil_scoped_acquire acquire;
      progress(stage, fraction);
    };
  }
  Eigen::MatrixX3d corrected;
  CorrectionReport report;
  {
    py::gil_scoped_release release;
    std::unique_ptr<Device> device = create_device(device_name);
    corrected = correct_pose(reference_vertices.matrix(), target_vertices.matrix(), faces.matrix(), *device, options,
                             &report, callback);
  }
  return py::make_tuple(py::cast(std::move(corrected)), to_python(cli::correction_report_json(report)));
}

py::tuple correct_sequence_python(const py::object& reference, const py::object& frames, const py::object& f,
                                  double smoothing, bool carry, const py::object& earlier, const py::object& progress,
                                  const py::kwargs& keywords) {
  const VerticesArgument reference_vertices(reference, "V_ref");
  const FacesArgument faces(f, "F");
  const std::vector<Eigen::MatrixX3d> frame_vertices = vertices_list(frames, "frames");
  std::vector<Eigen::MatrixX3d> earlier_vertices;
  if (!earlier.is_none()) {
    size_t index = 0;
    for (const py::handle item : earlier) {
      earlier_vertices.emplace_back(
          item.is_none() ? Eigen::MatrixX3d() : Eigen::MatrixX3d(VerticesArgument(item, "earlier[" + std::to_string(index) + "]").matrix()));
      ++index;
    }
  }
  SequenceCorrectionOptions options;
  std::string device_name;
  options.frame = correction_options_from(keywords, "correct_sequence", static_cast<int>(reference_vertices.matrix().rows()),
                                          device_name);
  options.smoothing_frames = smoothing;
  options.carry_corrections = carry;
  SequenceCallbacks callbacks;
  if (!progress.is_none()) {
    callbacks.progress = [&progress](int done, int total) {
      py::gil_scoped_acquire acquire;
      progress(done, total);
    };
  }
  std::vector<FrameCorrection> results;
  SequenceReport report;
  std::string device_description;
  {
    py::gil_scoped_release release;
    std::unique_ptr<Device> device = create_device(device_name);
    device_description = device->info().backend + ": " + device->info().name;
    results = correct_sequence(reference_vertices.matrix(), frame_vertices, faces.matrix(), *device, options, &report,
                               callbacks, earlier.is_none() ? nullptr : &earlier_vertices);
  }
  std::vector<std::string> names;
  for (size_t t = 0; t < results.size(); ++t) names.push_back("frame " + std::to_string(t));
  const nlohmann::json json = cli::sequence_report_json(report, results, names, device_description);
  py::list frames_out;
  for (size_t t = 0; t < results.size(); ++t) {
    py::object vertices = results[t].error.empty() ? py::cast(std::move(results[t].vertices)) : py::none();
    frames_out.append(py::make_tuple(vertices, to_python(json.at("frames")[t])));
  }
  return py::make_tuple(frames_out, to_python(json.at("sequence")));
}

// One weight vector: a number t for two poses, or one weight per pose.
Eigen::VectorXd weight_vector(const py::handle& value, int pose_count) {
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    if (pose_count != 2) {
      throw ArgumentError("a single weight t is for two poses; give one weight per pose for " + std::to_string(pose_count));
    }
    return two_pose_weights(value.cast<double>());
  }
  const std::vector<double> values = value.cast<std::vector<double>>();
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

py::object interpolate_python(const py::object& poses, const py::object& f, const py::object& weights,
                              const py::object& progress, const py::kwargs& keywords) {
  const FacesArgument faces(f, "F");
  std::vector<Eigen::MatrixX3d> pose_vertices = vertices_list(poses, "poses");
  CLI::App app{"interpolate", "interpolate"};
  cli::InterpolationFlags flags;
  cli::add_interpolation_flags(&app, flags);
  parse_keywords(app, keywords);
  const InterpolationOptions options = cli::interpolation_options(flags);
  // A list of weight vectors (or of numbers t) gives a list of poses from one precomputation.
  const bool several = !(py::isinstance<py::float_>(weights) || py::isinstance<py::int_>(weights)) &&
                       py::len(weights) > 0 && !(py::isinstance<py::float_>(weights[py::int_(0)]) ||
                                                 py::isinstance<py::int_>(weights[py::int_(0)]));
  std::vector<Eigen::VectorXd> vectors;
  const int pose_count = static_cast<int>(pose_vertices.size());
  if (several) {
    for (const py::handle item : weights) vectors.push_back(weight_vector(item, pose_count));
  } else {
    vectors.push_back(weight_vector(weights, pose_count));
  }
  std::vector<std::pair<Eigen::MatrixX3d, nlohmann::json>> results;
  {
    py::gil_scoped_release release;
    PoseSet set(faces.matrix());
    for (Eigen::MatrixX3d& pose : pose_vertices) set.add_pose(std::move(pose));
    const StageProgress report(progress);
    report("precomputation", 0.0);
    PoseInterpolator interpolator(std::move(set), options);
    report("precomputation", 1.0);
    for (size_t i = 0; i < vectors.size(); ++i) {
      report("interpolation", static_cast<double>(i) / static_cast<double>(vectors.size()));
      InterpolationStepReport step;
      Eigen::MatrixX3d pose = interpolator.interpolate(vectors[i], &step);
      const InterpolationError error = interpolator.error(pose, vectors[i]);
      results.emplace_back(std::move(pose), cli::interpolation_step_json(vectors[i], step, error));
    }
    report("interpolation", 1.0);
  }
  py::list out;
  for (auto& [pose, report] : results) out.append(py::make_tuple(py::cast(std::move(pose)), to_python(report)));
  return several ? py::object(out) : py::object(out[0]);
}

// The examples as a pose set, checked against the constrained vertices.
PoseSet example_set(std::vector<Eigen::MatrixX3d> examples, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                    const std::vector<int>& constrained, const std::string& function) {
  if (examples.empty()) throw ArgumentError(function + ": no example pose");
  PoseSet set(faces);
  for (size_t k = 0; k < examples.size(); ++k) set.add_pose(std::move(examples[k]), "example " + std::to_string(k));
  for (const int v : constrained) {
    if (v < 0 || v >= set.vertex_count()) {
      throw ArgumentError(function + ": constrained vertex " + std::to_string(v) + " is not in [0, " +
                          std::to_string(set.vertex_count()) + ")");
    }
  }
  return set;
}

// The skinning weights a caller gave (n x w), or an empty matrix for None.
Eigen::MatrixXd skinning_weights(const py::object& weights) {
  return weights.is_none() ? Eigen::MatrixXd() : weights.cast<Eigen::MatrixXd>();
}

void check_point_count(const std::string& function, size_t vertices, Eigen::Index positions) {
  if (static_cast<Eigen::Index>(vertices) != positions) {
    throw ArgumentError(function + ": " + std::to_string(vertices) + " vertices but " + std::to_string(positions) +
                        " positions");
  }
}

// The deformer of `set`: from the given skinning weights, or from the options' eigenfunctions.
BlendedDeformer deformer_of(const PoseSet& set, const cli::BlendCommandOptions& options, const Eigen::MatrixXd& skinning) {
  if (skinning.size() == 0) return cli::make_deformer(set, options);
  if (options.dictionary != "lbo") {
    throw ArgumentError("weights are a dictionary of their own; they cannot be combined with dictionary=" +
                        options.dictionary);
  }
  BlendOptions blend = options.blend;
  blend.estimate_scale = !options.no_scale;
  return BlendedDeformer(set, skinning, blend);
}

py::tuple register_python(const py::object& examples, const py::object& f, const py::object& scan_v,
                          const py::object& scan_f, const py::object& vertices, const py::object& positions,
                          const py::object& weights, const py::object& progress, const py::kwargs& keywords) {
  const FacesArgument faces(f, "F");
  std::vector<Eigen::MatrixX3d> example_vertices = vertices_list(examples, "examples");
  const VerticesArgument scan_vertices(scan_v, "scan_V");
  const FacesArgument scan_faces(scan_f, "scan_F");
  const VerticesArgument feature_positions(positions, "positions");
  const std::vector<int> features = vertices.cast<std::vector<int>>();
  check_point_count("register", features.size(), feature_positions.matrix().rows());
  CLI::App app{"register", "register"};
  cli::BlendCommandOptions options;
  ScanFitOptions fit;
  cli::add_blend_tuning_options(&app, options);
  cli::add_scan_fit_options(&app, fit);
  parse_keywords(app, keywords);
  const Eigen::MatrixXd skinning = skinning_weights(weights);
  nlohmann::json report;
  Eigen::MatrixX3d result;
  {
    py::gil_scoped_release release;
    const StageProgress stage(progress);
    const PoseSet set = example_set(std::move(example_vertices), faces.matrix(), features, "register");
    stage("setup", 0.0);
    BlendedDeformer deformer = deformer_of(set, options, skinning);
    stage("setup", 1.0);
    const Mesh scan{scan_vertices.matrix(), scan_faces.matrix()};
    stage("registration", 0.0);
    const ScanRegistration registration = register_partial_scan(deformer, scan, features, feature_positions.matrix(), fit);
    stage("registration", 1.0);
    cli::registration_json(registration, set, deformer, report);
    report["features"] = features.size();
    result = registration.deformation.vertices;
  }
  return py::make_tuple(py::cast(std::move(result)), to_python(report));
}

py::tuple deform_python(const py::object& examples, const py::object& f, const py::object& vertices,
                        const py::object& positions, const py::object& weights, const py::object& progress,
                        const py::kwargs& keywords) {
  const FacesArgument faces(f, "F");
  std::vector<Eigen::MatrixX3d> example_vertices = vertices_list(examples, "examples");
  const VerticesArgument targets(positions, "positions");
  PointConstraints constraints;
  constraints.vertices = vertices.cast<std::vector<int>>();
  constraints.positions = targets.matrix();
  constraints.groups.assign(constraints.vertices.size(), "");
  check_point_count("deform", constraints.vertices.size(), constraints.positions.rows());
  CLI::App app{"deform", "deform"};
  cli::BlendCommandOptions options;
  cli::add_blend_tuning_options(&app, options);
  parse_keywords(app, keywords);
  const Eigen::MatrixXd skinning = skinning_weights(weights);
  nlohmann::json report;
  Eigen::MatrixX3d result;
  {
    py::gil_scoped_release release;
    const StageProgress stage(progress);
    const PoseSet set = example_set(std::move(example_vertices), faces.matrix(), constraints.vertices, "deform");
    stage("setup", 0.0);
    BlendedDeformer deformer = deformer_of(set, options, skinning);
    stage("setup", 1.0);
    stage("deformation", 0.0);
    const BlendResult deformed = cli::deform_to_points(deformer, constraints, report);
    stage("deformation", 1.0);
    report["setup"] = cli::setup_json(deformer.setup_report());
    report["deformation"] = cli::deformation_json(deformed, set);
    result = deformed.vertices;
  }
  return py::make_tuple(py::cast(std::move(result)), to_python(report));
}

}  // namespace

PYBIND11_MODULE(_posekit, m) {
  m.doc() = "posekit: example-based processing of triangle-mesh poses";
  static py::exception<DeviceError> device_error(m, "DeviceError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) std::rethrow_exception(raised);
    } catch (const DeviceError& error) {
      device_error(error.what());
    } catch (const ArgumentError& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
    } catch (const InputError& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
    } catch (const Error& error) {
      PyErr_SetString(PyExc_RuntimeError, error.what());
    }
  });

  m.def("read_mesh", &read_mesh_python, "path"_a,
        "Reads a triangle mesh (OBJ, OFF or PLY): returns (V, F), V float64 n x 3, F int32 m x 3.\n"
        "ValueError names the file and the problem when it cannot be read.");
  m.def("write_mesh", &write_mesh_python, "path"_a, "V"_a, "F"_a,
        "Writes V (n x 3) and F (m x 3) in the format of the path's extension, whole or not at all.");
  m.def("devices", &devices_python,
        "The compute backends (cpu, opencl, vulkan, cuda): a dict each with its state, and its device or the reason "
        "it is unavailable.");
  m.def("check", &check_python, "V"_a, "F"_a, "reference"_a = py::none(),
        "Counts the self-intersecting faces of (V, F) and, with the reference's vertices, those that are new.");
  m.def("correct", &correct_python, "V_ref"_a, "V_target"_a, "F"_a, py::kw_only(), "progress"_a = py::none(),
        "Removes the self-intersections of V_target that V_ref does not have (docs/correct.md).\n\n"
        "V_ref, V_target: float64 n x 3 (the clean reference, the pose to correct); F: int m x 3, shared.\n"
        "progress: called with (stage, fraction done).\n"
        "Options are those of `posekit correct`, as keywords: device='auto', key_frames=11, collar_rings=3,\n"
        "whole_mesh=False, no_<stage>=True to skip a repair stage, exclude=[vertex indices], ...\n"
        "Returns (V, report): the corrected vertices and the report as a dict (the --report JSON).");
  m.def("interpolate", &interpolate_python, "poses"_a, "F"_a, "weights"_a, py::kw_only(), "progress"_a = py::none(),
        "In-between poses of one shape (docs/interpolate.md).\n\n"
        "poses: a sequence of K float64 n x 3 arrays sharing F (int m x 3). weights: a number t for two poses\n"
        "((1 - t, t)), K weights summing to 1, or a list of those for several poses from one precomputation.\n"
        "progress: called with (stage, fraction done): precomputation, then interpolation.\n"
        "Options are those of `posekit interpolate`, as keywords: method='mixit' (or 'edge', 'vertex'),\n"
        "joint_width, refinement_iterations, projection_passes, edge_iterations, bending_weight, ...\n"
        "Returns (V, report), or a list of those for a list of weights; the report holds the weights, the\n"
        "errors against the interpolated edge lengths and dihedral angles, and the seconds of each step.");
  m.def("deform", &deform_python, "examples"_a, "F"_a, "vertices"_a, "positions"_a, py::kw_only(),
        "weights"_a = py::none(), "progress"_a = py::none(),
        "A natural pose from a few point constraints, learned from example poses (docs/deform-register.md).\n\n"
        "examples: a sequence of float64 n x 3 poses sharing F (int m x 3), the first the reference.\n"
        "vertices: the constrained vertex indices; positions: their k x 3 target positions.\n"
        "weights: n x w skinning weights instead of Laplace-Beltrami eigenfunctions. progress: called with\n"
        "(stage, fraction done): setup, then deformation. Options are those of\n"
        "`posekit deform`, as keywords: eigenfunctions, atom_fraction, clusters, constraint_weight, ...\n"
        "Returns (V, report): the deformed pose and its setup and deformation report.");
  m.def("register", &register_python, "examples"_a, "F"_a, "scan_V"_a, "scan_F"_a, "vertices"_a, "positions"_a,
        py::kw_only(), "weights"_a = py::none(), "progress"_a = py::none(),
        "Completes a partial scan: the examples' full mesh fitted to it (docs/deform-register.md).\n\n"
        "examples: float64 n x 3 poses sharing F (int m x 3), the first the reference. scan_V, scan_F: the\n"
        "scan's triangle mesh. vertices, positions: mesh vertices and their k x 3 positions on the scan.\n"
        "weights: n x w skinning weights instead of eigenfunctions. progress: called with (stage, fraction\n"
        "done): setup, then registration. Options are those of `posekit register`,\n"
        "as keywords: icp_iterations, scan_points, scan_weight, normal_angle, eigenfunctions, ...\n"
        "Returns (V, report): the fitted mesh and the report (ICP rounds, the mesh vertex of each scan vertex).");
  m.def("blend_radius", &blend_radius, "smoothing"_a,
        "Frames on each side whose corrections the blend of a frame reads, for this smoothing.");
  m.def("correct_sequence", &correct_sequence_python, "V_ref"_a, "frames"_a, "F"_a, py::kw_only(),
        "smoothing"_a = SequenceCorrectionOptions{}.smoothing_frames, "carry"_a = true, "earlier"_a = py::none(),
        "progress"_a = py::none(),
        "Corrects every frame of an animation against V_ref, coherently in time (docs/correct-sequence.md).\n\n"
        "frames: a sequence of float64 n x 3 arrays, in time order; F: int m x 3, shared.\n"
        "smoothing: standard deviation in frames of the blend of the corrections; carry: try the previous\n"
        "frame's correction first. earlier: per frame, its own correction from an earlier run (reused) or None.\n"
        "progress: called with (frames done, frames). Other options as in correct().\n"
        "Returns (frames, sequence): a (V, report) per frame in order (V None where it failed) and the\n"
        "sequence's report as a dict.");
}

}  // namespace posekit::python

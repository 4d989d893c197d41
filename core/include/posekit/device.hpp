// The compute-device interface: the three data-parallel operations that every backend implements.
//
// Points live in R^4 as (x, y, z, t). An RBF field f: R^4 -> R^3 is
//   f(y) = sum_j w_j phi(|y - c_j|) + sum_k p_k pi_k(y),   phi(r) = r^2 ln r, phi(0) = 0,
// with the 15 quadratic monomials pi_k of R^4 in the order of kernel_math.h. Everything is fp64.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace posekit {

/// Number of quadratic polynomial terms in R^4: 1, x, y, z, t and the 10 second-order monomials.
constexpr int kRbfPolynomialTerms = 15;

/// #P by 4 list of points (x, y, z, t), one per row.
using Points4 = Eigen::Matrix<double, Eigen::Dynamic, 4>;
/// 15 by 3 polynomial coefficients, one column per output component.
using RbfPolynomial = Eigen::Matrix<double, kRbfPolynomialTerms, 3>;

/// An RBF field on the host: centers, their weights and the polynomial part.
struct RbfField {
  Points4 centers;            ///< #C by 4 centers c_j
  Eigen::MatrixX3d weights;   ///< #C by 3 weights w_j
  RbfPolynomial polynomial = RbfPolynomial::Zero();
};

/// A field stored on a device by Device::upload_field; evaluate or integrate against it many times.
/// It carries the number of the device that holds it, so that a device refuses another's field.
class DeviceField {
 public:
  virtual ~DeviceField() = default;
  DeviceField(const DeviceField&) = delete;
  DeviceField& operator=(const DeviceField&) = delete;

  int center_count() const { return center_count_; }
  /// Device::id of the device that holds it.
  std::uint64_t device_id() const { return device_id_; }

 protected:
  DeviceField(std::uint64_t device_id, int center_count)
      : device_id_(device_id), center_count_(center_count) {}

 private:
  std::uint64_t device_id_;
  int center_count_;
};

/// How the adaptive Dormand-Prince 5(4) integration chooses its steps. A step is accepted when the
/// root mean square over x, y, z of its local error estimate e_i / (absolute_tolerance +
/// relative_tolerance * |x_i|) is at most 1 (positions in their own units, steps in those of t).
struct Rk45StepControl {
  double relative_tolerance = 1e-7;    ///< per-component relative error per step (>= 0, finite)
  double absolute_tolerance = 1e-9;    ///< per-component absolute error per step (> 0, finite)
  double initial_step = 1e-2;          ///< first trial step, as a length of time (> 0, finite)
  double min_step = 1e-12;             ///< a particle whose step falls below this fails (>= 0)
  int max_steps = 100000;              ///< accepted plus rejected steps before a particle fails (> 0)
};

/// One integration: from t_begin to t_end (finite; t_end < t_begin integrates backwards) under the
/// step control. Device::integrate_rk45 throws ArgumentError naming an option out of its range.
struct Rk45Options : Rk45StepControl {
  double t_begin = 0.0;                ///< start time of every particle
  double t_end = 1.0;                  ///< end time of every particle
};

/// How one particle's integration ended.
enum class Rk45Status : std::int32_t { ok = 0, max_steps = 1, step_underflow = 2, non_finite = 3 };

/// Per-particle statistics of one integration.
struct Rk45ParticleStats {
  std::int32_t accepted_steps = 0;
  std::int32_t rejected_steps = 0;
  std::int32_t rhs_evaluations = 0;  ///< evaluations of the field f(x, t)
  Rk45Status status = Rk45Status::ok;
};

/// Totals over a batch of particles.
struct Rk45Summary {
  long long accepted_steps = 0;
  long long rejected_steps = 0;
  long long rhs_evaluations = 0;
  long long failures = 0;  ///< particles whose status is not ok
};

/// Throws ArgumentError naming the first option out of range (non-finite times or tolerances,
/// absolute_tolerance <= 0, initial_step <= 0, min_step < 0, max_steps <= 0), as
/// Device::integrate_rk45 does before any work.
void validate_rk45_options(const Rk45Options& options);

/// The same checks for the step control alone (as correct_pose() does for its options).
void validate_rk45_step_control(const Rk45StepControl& options);

/// Adds up per-particle statistics.
Rk45Summary summarize(const std::vector<Rk45ParticleStats>& stats);

/// What a device is and what it can do.
struct DeviceInfo {
  std::string backend;      ///< "cpu", "opencl", "vulkan" or "cuda"
  std::string name;         ///< the device's own name (e.g. the GPU model or "4 threads")
  std::string driver;       ///< driver or platform, where the API reports one
  bool fp64 = false;        ///< native double precision; no backend falls back to float
  bool emulated_on_cpu = false;  ///< a CPU implementation of a GPU API (PoCL, lavapipe)
  std::uint64_t max_buffer_bytes = 0;  ///< largest single buffer, 0 when unlimited
  int compute_units = 0;
};

/// A compute device. Kernels and pipelines are built once, when the device is created.
/// The public operations check their arguments once, for every backend alike, and throw
/// ArgumentError on inconsistent sizes or a field of another device; DeviceError on an API failure.
class Device {
 public:
  virtual ~Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  virtual DeviceInfo info() const = 0;

  /// Writes into `block` (#P by #C, plus 15 columns when with_polynomial) the values
  /// phi(|points_i - centers_j|) followed by the polynomial terms pi_k(points_i).
  void assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                          const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                          Eigen::Ref<Eigen::MatrixXd> block);

  /// Stores a field on the device for repeated evaluation and integration. Throws ArgumentError
  /// unless the weights have one row per center.
  std::unique_ptr<DeviceField> upload_field(const RbfField& field);

  /// Writes f(points_i) into row i of `values` (#P by 3).
  void evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                    Eigen::Ref<Eigen::MatrixX3d> values);

  /// Integrates every particle x (row of `positions`, #P by 3, overwritten with the end positions)
  /// through dx/dt = f(x, t) from options.t_begin to options.t_end, each with its own adaptive step.
  /// Returns one statistics record per particle. A particle that fails is not an exception: its
  /// status says why and its row holds the position it had reached.
  std::vector<Rk45ParticleStats> integrate_rk45(const DeviceField& field,
                                                Eigen::Ref<Eigen::MatrixX3d> positions,
                                                const Rk45Options& options);

  /// A number unique to this device in the process; the fields it holds carry it.
  std::uint64_t id() const { return id_; }

 protected:
  /// Whether callers' threads may enter the operations together (the CPU's thread arena) or one
  /// at a time (a GPU API's queue or stream).
  enum class Calls { concurrent, serialized };
  explicit Device(Calls calls);

  // The backend's operations. They are called with checked arguments: the shapes agree, the
  // options are valid, there is work to do, and a field was uploaded to this device, so that its
  // dynamic type is the backend's own (see uploaded()).
  virtual void do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                                     const Eigen::Ref<const Points4>& centers,
                                     bool with_polynomial, Eigen::Ref<Eigen::MatrixXd> block) = 0;
  virtual std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) = 0;
  virtual void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                               Eigen::Ref<Eigen::MatrixX3d> values) = 0;
  virtual std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField& field,
                                                           Eigen::Ref<Eigen::MatrixX3d> positions,
                                                           const Rk45Options& options) = 0;

  /// The backend's own field type of a field that the front has checked to be this device's.
  template <typename BackendField>
  static const BackendField& uploaded(const DeviceField& field) {
    return static_cast<const BackendField&>(field);
  }

 private:
  std::unique_lock<std::mutex> enter();

  std::uint64_t id_;
  Calls calls_;
  std::mutex mutex_;
};

}  // namespace posekit

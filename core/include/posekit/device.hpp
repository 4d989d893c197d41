// The compute-device interface: the three data-parallel operations that every backend implements.
//
// Points live in R^4 as (x, y, z, t). An RBF field f: R^4 -> R^3 is
//   f(y) = sum_j w_j phi(|y - c_j|) + sum_k p_k pi_k(y),   phi(r) = r^2 ln r, phi(0) = 0,
// with the 15 quadratic monomials pi_k of R^4 in the order of kernel_math.h. Everything is fp64.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
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
class DeviceField {
 public:
  virtual ~DeviceField() = default;
  virtual int center_count() const = 0;
};

/// The operations a backend may provide; ask Device::supports before relying on one.
enum class DeviceOperation { rbf_assembly, rbf_evaluation, rk45_integration };

/// Controls of the adaptive Dormand-Prince 5(4) integration. Times and tolerances must be finite,
/// relative_tolerance >= 0, absolute_tolerance > 0, initial_step > 0, min_step >= 0 and
/// max_steps > 0; Device::integrate_rk45 throws ArgumentError naming the option otherwise.
struct Rk45Options {
  double t_begin = 0.0;                ///< start time of every particle
  double t_end = 1.0;                  ///< end time of every particle
  double relative_tolerance = 1e-7;    ///< per-component relative error per step
  double absolute_tolerance = 1e-9;    ///< per-component absolute error per step
  double initial_step = 1e-2;          ///< first trial step, as a length of time
  double min_step = 1e-12;             ///< a particle whose step falls below this fails
  int max_steps = 100000;              ///< accepted plus rejected steps before a particle fails
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
/// absolute_tolerance <= 0, initial_step <= 0, min_step < 0, max_steps <= 0). Every backend calls it.
void validate_rk45_options(const Rk45Options& options);

/// Throws ArgumentError unless `block` is #points by (#centers + 15 when with_polynomial), as
/// Device::assemble_rbf_block needs; returns that column count. Every backend calls it.
Eigen::Index validate_rbf_block_shape(Eigen::Index point_count, Eigen::Index center_count, bool with_polynomial,
                                      const Eigen::Ref<Eigen::MatrixXd>& block);

/// Throws ArgumentError unless `values` has one row per point, as Device::evaluate_rbf needs.
void validate_rbf_values_shape(Eigen::Index point_count, const Eigen::Ref<Eigen::MatrixX3d>& values);

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
/// Methods throw DeviceError on an API failure and ArgumentError on inconsistent sizes.
class Device {
 public:
  virtual ~Device() = default;

  virtual DeviceInfo info() const = 0;
  virtual bool supports(DeviceOperation operation) const = 0;

  /// Writes into `block` (#P by #C, plus 15 columns when with_polynomial) the values
  /// phi(|points_i - centers_j|) followed by the polynomial terms pi_k(points_i).
  virtual void assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                                  const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                                  Eigen::Ref<Eigen::MatrixXd> block) = 0;

  /// Stores a field on the device for repeated evaluation and integration.
  virtual std::unique_ptr<DeviceField> upload_field(const RbfField& field) = 0;

  /// Writes f(points_i) into row i of `values` (#P by 3).
  virtual void evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                            Eigen::Ref<Eigen::MatrixX3d> values) = 0;

  /// Integrates every particle x (row of `positions`, #P by 3, overwritten with the end positions)
  /// through dx/dt = f(x, t) from options.t_begin to options.t_end, each with its own adaptive step.
  /// Returns one statistics record per particle. A particle that fails is not an exception: its
  /// status says why and its row holds the position it had reached.
  virtual std::vector<Rk45ParticleStats> integrate_rk45(const DeviceField& field,
                                                        Eigen::Ref<Eigen::MatrixX3d> positions,
                                                        const Rk45Options& options) = 0;
};

}  // namespace posekit

// The greedy fit: spread-out starting centers, then rounds of evaluate / select / extend until
// every constraint is met or the center budget is spent.
#include <posekit/rbf_fitting.hpp>

#include <posekit/error.hpp>

#include "correct/center_selection.hpp"
#include "correct/rbf_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace posekit {
namespace {

using Eigen::Index;

// The 15 polynomial terms need at least 15 centers in general position; a few more keep the first
// system away from the edge of singularity, and a problem this small needs no greedy fit anyway.
constexpr Index kMinimumConstraints = 20;
// Centers of the first batch when centers_per_round is smaller than this.
constexpr Index kMinimumFirstBatch = 20;
// Smallest max_centers: the 15 polynomial terms plus the paper's two starting centers.
constexpr int kMinimumMaxCenters = kRbfPolynomialTerms + 2;
// Constraints closer than this fraction of the bounding-box diagonal count as one point: a second
// center there would repeat a row of the system.
constexpr double kCoincidentFraction = 1e-9;

void validate(const Points4& positions, const Eigen::Ref<const Eigen::MatrixX3d>& values,
              const RbfFitOptions& options) {
  if (options.centers_per_round < 1) {
    throw ArgumentError("RbfFitOptions::centers_per_round must be >= 1 (got " +
                        std::to_string(options.centers_per_round) + ")");
  }
  if (options.candidates < options.centers_per_round) {
    throw ArgumentError("RbfFitOptions::candidates must be >= centers_per_round (got " +
                        std::to_string(options.candidates) + " < " +
                        std::to_string(options.centers_per_round) + ")");
  }
  if (!(std::isfinite(options.max_squared_error) && options.max_squared_error > 0.0)) {
    throw ArgumentError("RbfFitOptions::max_squared_error must be finite and > 0 (got " +
                        std::to_string(options.max_squared_error) + ")");
  }
  if (options.max_centers < kMinimumMaxCenters) {
    throw ArgumentError("RbfFitOptions::max_centers must be >= " +
                        std::to_string(kMinimumMaxCenters) + " (got " +
                        std::to_string(options.max_centers) + ")");
  }
  if (positions.rows() != values.rows()) {
    throw ArgumentError("fit_rbf_field: positions has " + std::to_string(positions.rows()) +
                        " rows but values has " + std::to_string(values.rows()));
  }
  if (positions.rows() < kMinimumConstraints) {
    throw ArgumentError("fit_rbf_field: " + std::to_string(positions.rows()) +
                        " constraints are too few (at least " +
                        std::to_string(kMinimumConstraints) + ")");
  }
  for (Index i = 0; i < positions.rows(); ++i) {
    if (!positions.row(i).allFinite()) {
      throw ArgumentError("fit_rbf_field: positions row " + std::to_string(i) +
                          " is not finite");
    }
    if (!values.row(i).allFinite()) {
      throw ArgumentError("fit_rbf_field: values row " + std::to_string(i) + " is not finite");
    }
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Points4 rows_of(const Points4& points, const std::vector<Index>& indices) {
  Points4 selected(static_cast<Index>(indices.size()), 4);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    selected.row(static_cast<Index>(k)) = points.row(indices[k]);
  }
  return selected;
}

Eigen::MatrixX3d center_values(const Eigen::Ref<const Eigen::MatrixX3d>& values,
                               const std::vector<Index>& center_rows) {
  Eigen::MatrixX3d selected(static_cast<Index>(center_rows.size()), 3);
  for (std::size_t k = 0; k < center_rows.size(); ++k) selected.row(static_cast<Index>(k)) = values.row(center_rows[k]);
  return selected;
}

}  // namespace

RbfField fit_rbf_field(Device& device, const Points4& positions, const Eigen::Ref<const Eigen::MatrixX3d>& values,
                       const RbfFitOptions& options, RbfFitReport* report) {
  RbfFit fit(device, positions, values, options);
  if (report != nullptr) *report = fit.report();
  return fit.field();
}

RbfFit::~RbfFit() = default;
RbfFit::RbfFit(RbfFit&&) noexcept = default;
RbfFit& RbfFit::operator=(RbfFit&&) noexcept = default;

RbfField RbfFit::refit(const Eigen::Ref<const Eigen::MatrixX3d>& values) const {
  if (values.rows() != constraint_count_) {
    throw ArgumentError("RbfFit::refit: values has " + std::to_string(values.rows()) + " rows but the fit has " +
                        std::to_string(constraint_count_) + " constraints");
  }
  return system_->solve(center_values(values, center_rows_));
}

RbfFit::RbfFit(Device& device, const Points4& positions, const Eigen::Ref<const Eigen::MatrixX3d>& values,
               const RbfFitOptions& options) {
  validate(positions, values, options);
  constraint_count_ = positions.rows();
  const Index count = positions.rows();
  const Index max_centers = std::min<Index>(options.max_centers, count);
  const double diagonal =
      (positions.colwise().maxCoeff() - positions.colwise().minCoeff()).norm();
  const double min_separation = kCoincidentFraction * diagonal;

  RbfFitReport& out = report_;
  system_ = std::make_unique<detail::RbfSystem>(device, options.blocked_update, max_centers);
  detail::RbfSystem& system = *system_;
  std::vector<bool> is_center(static_cast<std::size_t>(count), false);
  std::vector<Index>& center_indices = center_rows_;

  // The paper starts from the two most distant constraints. Alone they leave the 15 polynomial
  // terms undetermined (the system is singular below 15 centers), so farthest-point sampling,
  // which begins with that pair, fills the first batch to a full round's worth of centers.
  std::vector<Index> batch = detail::spread_centers(
      positions, std::min(std::max<Index>(options.centers_per_round, kMinimumFirstBatch), max_centers),
      min_separation);

  detail::CenterCandidates selection;
  selection.candidates = options.candidates;
  selection.max_squared_error = options.max_squared_error;
  selection.min_separation = min_separation;

  RbfField& field = field_;
  Eigen::MatrixX3d predicted(count, 3);
  for (;;) {
    RbfFitRound round;
    const detail::RbfSystemTimes times = system.add_centers(rows_of(positions, batch));
    for (const Index index : batch) {
      is_center[static_cast<std::size_t>(index)] = true;
      center_indices.push_back(index);
    }
    round.assembly_seconds = times.assembly;

    auto start = std::chrono::steady_clock::now();
    field = system.solve(center_values(values, center_indices));
    round.factorization_seconds = times.factorization + seconds_since(start);

    start = std::chrono::steady_clock::now();
    const std::unique_ptr<DeviceField> device_field = device.upload_field(field);
    device.evaluate_rbf(*device_field, positions, predicted);
    const Eigen::VectorXd squared_errors = (predicted - values).rowwise().squaredNorm();
    round.evaluation_seconds = seconds_since(start);
    if (!squared_errors.allFinite()) {
      throw Error("the fitted RBF field is not finite at some constraint (" +
                  std::to_string(system.center_count()) + " centers)");
    }

    round.centers = static_cast<int>(system.center_count());
    round.max_squared_error = squared_errors.maxCoeff();
    out.rounds.push_back(round);
    out.centers = round.centers;
    out.max_squared_error = round.max_squared_error;
    if (round.max_squared_error < options.max_squared_error) {
      out.converged = true;
      break;
    }
    const Index room = max_centers - system.center_count();
    if (room <= 0) break;
    selection.count = static_cast<int>(std::min<Index>(options.centers_per_round, room));
    batch = detail::select_new_centers(positions, squared_errors, is_center, system.centers(),
                                       selection);
    // Every badly fitted constraint left coincides with a center: more centers cannot help.
    if (batch.empty()) break;
  }
}

}  // namespace posekit

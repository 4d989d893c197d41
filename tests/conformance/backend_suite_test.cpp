// The conformance suite: every case (conformance.hpp says how to add one) on every backend the
// registry lists, plus the argument checks every backend owes and the guards that keep a run that
// tested nothing from passing.
//
// A backend that is not built or not available here is skipped with the registry's reason, unless
// POSEKIT_EXPECT_BACKENDS (comma-separated, e.g. "cpu,opencl,vulkan") names it: then it fails.
#include "conformance.hpp"

#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

namespace posekit::conformance {
namespace {

std::vector<std::string> registered_backends() {
  std::vector<std::string> names;
  for (const BackendStatus& status : list_backends()) names.push_back(status.name);
  return names;
}

CaseList all_cases() {
  CaseList cases = rbf_assembly_cases();
  for (CaseList more : {rbf_evaluate_cases(), rk45_cases()}) {
    cases.insert(cases.end(), more.begin(), more.end());
  }
  return cases;
}

bool is_expected(const std::string& backend) {
  const std::vector<std::string> expected = expected_backends();
  return std::find(expected.begin(), expected.end(), backend) != expected.end();
}

// One device per backend and process: GPU backends compile their kernels when a device is created.
// Returns nullptr with the reason when the backend cannot run here.
Device* acquire_device(const std::string& backend, std::string& reason) {
  static std::map<std::string, std::unique_ptr<Device>> devices;
  static std::map<std::string, std::string> reasons;
  if (const auto found = devices.find(backend); found != devices.end()) return found->second.get();
  if (const auto found = reasons.find(backend); found != reasons.end()) {
    reason = found->second;
    return nullptr;
  }
  for (const BackendStatus& status : list_backends()) {
    if (status.name != backend) continue;
    if (status.state != BackendState::available) {
      reason = backend + " is " + to_string(status.state) + ": " + status.reason;
      reasons[backend] = reason;
      return nullptr;
    }
    try {
      devices[backend] = create_device(backend);
      return devices[backend].get();
    } catch (const std::exception& error) {
      reason = backend + " is available but its device could not be created: " + error.what();
      reasons[backend] = reason;
      return nullptr;
    }
  }
  reason = backend + " is not registered";
  return nullptr;
}

// Conformance cases started and cases that got to run on a device, in this process.
struct RunCounters {
  int attempted = 0;
  int tested = 0;
};
RunCounters& counters() {
  static RunCounters counters;
  return counters;
}

// When this process ran several cases (the whole suite, not one test per process as under CTest)
// and every one of them skipped, the run tested nothing and must not pass.
class NothingTestedGuard : public ::testing::Environment {
 public:
  void TearDown() override {
    if (counters().attempted > 1 && counters().tested == 0) {
      ADD_FAILURE() << counters().attempted
                    << " conformance cases ran and every one was skipped: no backend was tested";
    }
  }
};
::testing::Environment* const nothing_tested_guard =
    ::testing::AddGlobalTestEnvironment(new NothingTestedGuard);

// Binds `device` (a Device&) for the current test, or skips (fails when the backend is expected).
#define POSEKIT_DEVICE_OR_SKIP(device, backend)                                              \
  std::string device##_reason;                                                               \
  Device* const device##_pointer = acquire_device(backend, device##_reason);                 \
  if (device##_pointer == nullptr) {                                                         \
    if (is_expected(backend)) FAIL() << "POSEKIT_EXPECT_BACKENDS lists " << device##_reason; \
    GTEST_SKIP() << device##_reason;                                                         \
  }                                                                                          \
  Device& device = *device##_pointer  // NOLINT(bugprone-macro-parentheses): a declarator

using CaseParameter = std::tuple<std::string, std::shared_ptr<const ConformanceCase>>;

class BackendConformance : public ::testing::TestWithParam<CaseParameter> {};

TEST_P(BackendConformance, MatchesReference) {
  const std::string& backend = std::get<0>(GetParam());
  const ConformanceCase& test_case = *std::get<1>(GetParam());
  ++counters().attempted;
  POSEKIT_DEVICE_OR_SKIP(device, backend);
  ++counters().tested;
  SCOPED_TRACE(backend + ": " + test_case.name());
  test_case.run(device);
}

INSTANTIATE_TEST_SUITE_P(Case, BackendConformance,
                         ::testing::Combine(::testing::ValuesIn(registered_backends()),
                                            ::testing::ValuesIn(all_cases())),
                         [](const ::testing::TestParamInfo<CaseParameter>& info) {
                           return sanitize_name(std::get<0>(info.param)) + "_" +
                                  std::get<1>(info.param)->name();
                         });

// Expects `call` to throw ArgumentError whose one-line message mentions `argument`.
void expect_argument_error(const std::function<void()>& call, const std::string& argument) {
  try {
    call();
    ADD_FAILURE() << "no ArgumentError for a bad " << argument;
  } catch (const ArgumentError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(argument), std::string::npos)
        << "the message should name " << argument << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line expected: " << message;
  } catch (const std::exception& error) {
    ADD_FAILURE() << "a bad " << argument
                  << " threw something other than ArgumentError: " << error.what();
  }
}

class BackendArguments : public ::testing::TestWithParam<std::string> {};

TEST_P(BackendArguments, RejectInconsistentSizes) {
  POSEKIT_DEVICE_OR_SKIP(device, GetParam());
  Random random(21);
  const Points4 points = random.points(5);
  const RbfField field = random.field(random.points(7), 1.0, 1.0);
  Eigen::MatrixXd without_polynomial_columns(5, 7);
  expect_argument_error(
      [&] { device.assemble_rbf_block(points, field.centers, true, without_polynomial_columns); },
      "block");
  Eigen::MatrixXd too_few_rows(4, 7);
  expect_argument_error(
      [&] { device.assemble_rbf_block(points, field.centers, false, too_few_rows); }, "block");
  RbfField mismatched = field;
  mismatched.weights.conservativeResize(6, 3);
  expect_argument_error([&] { device.upload_field(mismatched); }, "weights");
  const std::unique_ptr<DeviceField> uploaded = device.upload_field(field);
  Eigen::MatrixX3d too_many_rows(6, 3);
  expect_argument_error([&] { device.evaluate_rbf(*uploaded, points, too_many_rows); }, "values");
}

TEST_P(BackendArguments, RejectFieldsOfOtherDevices) {
  POSEKIT_DEVICE_OR_SKIP(device, GetParam());
  Random random(22);
  const Points4 points = random.points(5);
  const RbfField field = random.field(random.points(7), 1.0, 1.0);
  const std::unique_ptr<Device> other_device = create_device(GetParam());
  const std::unique_ptr<DeviceField> foreign = other_device->upload_field(field);

  // A field of no device: number 0 is never a device's.
  class UnknownField : public DeviceField {
   public:
    UnknownField() : DeviceField(0, 0) {}
  } unknown;

  Eigen::MatrixX3d values(5, 3);
  Eigen::MatrixX3d positions = points.leftCols<3>();
  for (const DeviceField* wrong : {static_cast<const DeviceField*>(foreign.get()),
                                   static_cast<const DeviceField*>(&unknown)}) {
    expect_argument_error([&] { device.evaluate_rbf(*wrong, points, values); }, "field");
    expect_argument_error([&] { device.integrate_rk45(*wrong, positions, Rk45Options()); },
                          "field");
  }
  EXPECT_EQ(positions, points.leftCols<3>()) << "a rejected call must not move particles";
}

TEST_P(BackendArguments, RejectInvalidRk45Options) {
  POSEKIT_DEVICE_OR_SKIP(device, GetParam());
  Random random(23);
  const RbfField field = random.field(random.points(7), 0.01, 0.01);
  const std::unique_ptr<DeviceField> uploaded = device.upload_field(field);
  const Eigen::MatrixX3d start = random.points(5).leftCols<3>();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, std::function<void(Rk45Options&)>>> invalid = {
      {"t_begin", [&](Rk45Options& o) { o.t_begin = nan; }},
      {"t_end", [&](Rk45Options& o) { o.t_end = inf; }},
      {"relative_tolerance", [](Rk45Options& o) { o.relative_tolerance = -1e-7; }},
      {"relative_tolerance", [&](Rk45Options& o) { o.relative_tolerance = nan; }},
      {"absolute_tolerance", [](Rk45Options& o) { o.absolute_tolerance = 0.0; }},
      {"absolute_tolerance", [](Rk45Options& o) { o.absolute_tolerance = -1e-9; }},
      {"initial_step", [](Rk45Options& o) { o.initial_step = 0.0; }},
      {"initial_step", [&](Rk45Options& o) { o.initial_step = inf; }},
      {"min_step", [](Rk45Options& o) { o.min_step = -1.0; }},
      {"max_steps", [](Rk45Options& o) { o.max_steps = 0; }},
  };
  for (const auto& [option, spoil] : invalid) {
    Rk45Options options;
    spoil(options);
    Eigen::MatrixX3d positions = start;
    expect_argument_error([&] { device.integrate_rk45(*uploaded, positions, options); }, option);
    EXPECT_EQ(positions, start) << "a rejected call must not move particles (" << option << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(Backend, BackendArguments, ::testing::ValuesIn(registered_backends()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return sanitize_name(info.param);
                         });

// Under CTest every test runs in a process of its own, so NothingTestedGuard cannot see the whole
// run; this test stands for it there: some registered backend must be able to run the cases.
TEST(ConformanceCoverage, AtLeastOneBackendIsTested) {
  int usable = 0;
  std::string reasons;
  for (const std::string& backend : registered_backends()) {
    std::string reason;
    Device* device = acquire_device(backend, reason);
    if (device != nullptr) {
      ++usable;
    } else {
      reasons += reason + "; ";
    }
  }
  EXPECT_GT(usable, 0) << "no backend can run the conformance cases: " << reasons;
}

TEST(ConformanceCoverage, ExpectedBackendsAreAvailable) {
  const std::vector<std::string> expected = expected_backends();
  if (expected.empty()) GTEST_SKIP() << "POSEKIT_EXPECT_BACKENDS is not set";
  const std::vector<std::string> registered = registered_backends();
  for (const std::string& backend : expected) {
    if (std::find(registered.begin(), registered.end(), backend) == registered.end()) {
      ADD_FAILURE() << "POSEKIT_EXPECT_BACKENDS lists " << backend
                    << ", which this build does not register";
      continue;
    }
    std::string reason;
    EXPECT_NE(acquire_device(backend, reason), nullptr)
        << "POSEKIT_EXPECT_BACKENDS lists " << reason;
  }
}

}  // namespace
}  // namespace posekit::conformance

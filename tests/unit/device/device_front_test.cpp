// Device's front: what every backend gets for free. A recording backend shows which calls reach
// it, so these tests hold the front itself rather than any one backend.
#include <posekit/device.hpp>
#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>
#include <vector>

namespace posekit {
namespace {

class RecordingField final : public DeviceField {
 public:
  RecordingField(std::uint64_t device_id, int center_count) : DeviceField(device_id, center_count) {}
};

// Counts the calls that reach the backend and the most that were inside it at once.
class RecordingDevice final : public Device {
 public:
  explicit RecordingDevice(Calls calls) : Device(calls) {}

  DeviceInfo info() const override { return {}; }

  int calls() const { return calls_; }
  int most_inside() const { return most_inside_; }
  using Device::Calls;

 protected:
  void do_assemble_rbf_block(const Eigen::Ref<const Points4>&, const Eigen::Ref<const Points4>&,
                             bool, Eigen::Ref<Eigen::MatrixXd> block) override {
    enter_and_wait();
    block.setOnes();
  }
  std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) override {
    enter_and_wait();
    return std::make_unique<RecordingField>(id(), static_cast<int>(field.centers.rows()));
  }
  void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>&,
                       Eigen::Ref<Eigen::MatrixX3d> values) override {
    enter_and_wait();
    values.setConstant(uploaded<RecordingField>(field).center_count());
  }
  std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField&,
                                                   Eigen::Ref<Eigen::MatrixX3d> positions,
                                                   const Rk45Options&) override {
    enter_and_wait();
    return std::vector<Rk45ParticleStats>(static_cast<std::size_t>(positions.rows()));
  }

 private:
  // Stays inside long enough that concurrent callers would overlap.
  void enter_and_wait() {
    ++calls_;
    const int inside = ++inside_;
    int most = most_inside_.load();
    while (inside > most && !most_inside_.compare_exchange_weak(most, inside)) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    --inside_;
  }

  std::atomic<int> calls_{0};
  std::atomic<int> inside_{0};
  std::atomic<int> most_inside_{0};
};

RbfField field_of(int centers) {
  RbfField field;
  field.centers = Points4::Zero(centers, 4);
  field.weights = Eigen::MatrixX3d::Zero(centers, 3);
  return field;
}

TEST(DeviceFront, RejectedCallsNeverReachTheBackend) {
  RecordingDevice device(RecordingDevice::Calls::concurrent);
  RecordingDevice other(RecordingDevice::Calls::concurrent);
  const std::unique_ptr<DeviceField> foreign = other.upload_field(field_of(2));
  const Points4 points = Points4::Zero(3, 4);
  Eigen::MatrixXd wrong_block(3, 2);
  EXPECT_THROW(device.assemble_rbf_block(points, points, true, wrong_block), ArgumentError);
  RbfField mismatched = field_of(2);
  mismatched.weights.resize(1, 3);
  EXPECT_THROW(device.upload_field(mismatched), ArgumentError);
  Eigen::MatrixX3d values(3, 3);
  EXPECT_THROW(device.evaluate_rbf(*foreign, points, values), ArgumentError);
  const std::unique_ptr<DeviceField> own = device.upload_field(field_of(2));
  Eigen::MatrixX3d wrong_values(2, 3);
  EXPECT_THROW(device.evaluate_rbf(*own, points, wrong_values), ArgumentError);
  Eigen::MatrixX3d positions = Eigen::MatrixX3d::Zero(3, 3);
  Rk45Options bad;
  bad.absolute_tolerance = 0.0;
  EXPECT_THROW(device.integrate_rk45(*own, positions, bad), ArgumentError);
  EXPECT_THROW(device.integrate_rk45(*foreign, positions, Rk45Options()), ArgumentError);
  EXPECT_EQ(device.calls(), 1) << "only the valid upload may reach the backend";
}

TEST(DeviceFront, EmptyWorkNeverReachesTheBackend) {
  RecordingDevice device(RecordingDevice::Calls::concurrent);
  const std::unique_ptr<DeviceField> field = device.upload_field(field_of(2));
  const Points4 none(0, 4);
  Eigen::MatrixXd empty_block(0, 2);
  device.assemble_rbf_block(none, Points4::Zero(2, 4), false, empty_block);
  Eigen::MatrixX3d no_values(0, 3);
  device.evaluate_rbf(*field, none, no_values);
  Eigen::MatrixX3d no_positions(0, 3);
  EXPECT_TRUE(device.integrate_rk45(*field, no_positions, Rk45Options()).empty());
  EXPECT_EQ(device.calls(), 1);
}

TEST(DeviceFront, AcceptedCallsReachTheBackendWithTheirOwnField) {
  RecordingDevice device(RecordingDevice::Calls::concurrent);
  const std::unique_ptr<DeviceField> field = device.upload_field(field_of(4));
  EXPECT_EQ(field->device_id(), device.id());
  Eigen::MatrixX3d values = Eigen::MatrixX3d::Zero(2, 3);
  device.evaluate_rbf(*field, Points4::Zero(2, 4), values);
  EXPECT_EQ(values, Eigen::MatrixX3d::Constant(2, 3, 4.0));
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(2, 3 + kRbfPolynomialTerms);
  device.assemble_rbf_block(Points4::Zero(2, 4), Points4::Zero(3, 4), true, block);
  EXPECT_EQ(block, Eigen::MatrixXd::Ones(2, 3 + kRbfPolynomialTerms));
  Eigen::MatrixX3d positions = Eigen::MatrixX3d::Zero(5, 3);
  EXPECT_EQ(device.integrate_rk45(*field, positions, Rk45Options()).size(), 5u);
  EXPECT_EQ(device.calls(), 4);
}

// Four threads call at once; returns the most calls that were inside the backend together.
int most_inside_under_four_callers(RecordingDevice::Calls calls) {
  RecordingDevice device(calls);
  const std::unique_ptr<DeviceField> field = device.upload_field(field_of(1));
  std::vector<std::thread> callers;
  for (int t = 0; t < 4; ++t) {
    callers.emplace_back([&] {
      Eigen::MatrixX3d values(1, 3);
      for (int i = 0; i < 3; ++i) device.evaluate_rbf(*field, Points4::Zero(1, 4), values);
    });
  }
  for (std::thread& caller : callers) caller.join();
  return device.most_inside();
}

TEST(DeviceFront, SerializedBackendsTakeOneCallerAtATime) {
  EXPECT_EQ(most_inside_under_four_callers(RecordingDevice::Calls::serialized), 1);
}

TEST(DeviceFront, ConcurrentBackendsLetCallersInTogether) {
  EXPECT_GT(most_inside_under_four_callers(RecordingDevice::Calls::concurrent), 1);
}

}  // namespace
}  // namespace posekit

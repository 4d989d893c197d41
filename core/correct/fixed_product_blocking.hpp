// Eigen's matrix products split their sums into blocks whose depth follows the L1 data cache it
// detects, so the same product rounds differently on processors whose caches differ; the fit's
// last bits, and the repair ladder's choices that follow them, would depend on the machine.
#pragma once

namespace posekit::detail {

/// While one exists, Eigen's cache sizes are fixed process-wide (48 KiB L1, 512 KiB L2, 32 MiB
/// L3), so that its products sum in the same blocks on every processor. Nested and concurrent ones
/// share the setting; the last to end gives back the sizes from before the first.
class FixedProductBlocking {
 public:
  FixedProductBlocking();
  ~FixedProductBlocking();
  FixedProductBlocking(const FixedProductBlocking&) = delete;
  FixedProductBlocking& operator=(const FixedProductBlocking&) = delete;
};

}  // namespace posekit::detail

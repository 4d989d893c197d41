// Eigen's matrix products split their sums into blocks whose depth follows the L1 data cache it
// detects, so the same product rounds differently on processors whose caches differ; the fit's
// last bits, and the repair ladder's choices that follow them, would depend on the machine.
#pragma once

namespace posekit::detail {

/// Sets Eigen's cache sizes, process-wide, to fixed values (48 KiB L1, 512 KiB L2, 32 MiB L3)
/// wherever they differ, so that its products sum in the same blocks on every processor.
void fix_eigen_product_blocking();

}  // namespace posekit::detail

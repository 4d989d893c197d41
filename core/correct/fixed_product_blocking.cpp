#include "correct/fixed_product_blocking.hpp"

#include <Eigen/Core>

#include <mutex>

namespace posekit::detail {

void fix_eigen_product_blocking() {
  // Any fixed values make the sums machine-independent; with these, a processor with another L1
  // reproduces the results measured before they were fixed (docs/correct.md, "On another
  // machine"). Only the L1 size sets the depth of a product's blocks (and with it the order of its
  // sums); the L2 size sets how small products are split into rows; the L3 size only has to be
  // nonzero.
  constexpr std::ptrdiff_t kL1Bytes = 48 * 1024;
  constexpr std::ptrdiff_t kL2Bytes = 512 * 1024;
  constexpr std::ptrdiff_t kL3Bytes = 32 * 1024 * 1024;
  // Checked at every correction, not once: the host may set its own sizes in between. Once they
  // are fixed, concurrent corrections only read them.
  static std::mutex setting;
  const std::lock_guard<std::mutex> lock(setting);
  if (Eigen::l1CacheSize() != kL1Bytes || Eigen::l2CacheSize() != kL2Bytes ||
      Eigen::l3CacheSize() != kL3Bytes) {
    Eigen::setCpuCacheSizes(kL1Bytes, kL2Bytes, kL3Bytes);
  }
}

}  // namespace posekit::detail

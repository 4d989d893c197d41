#include "correct/fixed_product_blocking.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <mutex>

namespace posekit::detail {
namespace {

// Any fixed values make the sums machine-independent; with these, a processor with another L1
// reproduces the results measured before they were fixed (docs/correct.md, "On another machine").
// Only the L1 size sets the depth of a product's blocks (and with it the order of its sums); the L2
// size sets how small products are split into rows; the L3 size only has to be nonzero.
constexpr std::ptrdiff_t kL1Bytes = 48 * 1024;
constexpr std::ptrdiff_t kL2Bytes = 512 * 1024;
constexpr std::ptrdiff_t kL3Bytes = 32 * 1024 * 1024;

// The sizes are the process's, so the holders are counted process-wide: the caller's own sizes
// come back once no correction runs, and the rest of the program (interpolation, deformation)
// computes with them as it did before any correction.
struct Holders {
  std::mutex mutex;
  int count = 0;
  std::ptrdiff_t l1 = 0;
  std::ptrdiff_t l2 = 0;
  std::ptrdiff_t l3 = 0;
};

Holders& holders() {
  static Holders instance;
  return instance;
}

}  // namespace

FixedProductBlocking::FixedProductBlocking() {
  Holders& h = holders();
  const std::lock_guard<std::mutex> lock(h.mutex);
  if (h.count++ > 0) return;
  h.l1 = Eigen::l1CacheSize();
  h.l2 = Eigen::l2CacheSize();
  h.l3 = Eigen::l3CacheSize();
  Eigen::setCpuCacheSizes(kL1Bytes, kL2Bytes, kL3Bytes);
}

FixedProductBlocking::~FixedProductBlocking() {
  Holders& h = holders();
  const std::lock_guard<std::mutex> lock(h.mutex);
  if (--h.count > 0) return;
  Eigen::setCpuCacheSizes(h.l1, h.l2, h.l3);
}

}  // namespace posekit::detail

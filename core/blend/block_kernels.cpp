#include "blend/block_kernels.hpp"

#include <algorithm>
#include <cstddef>

namespace posekit::detail {
namespace {

// One copy per x86-64 microarchitecture level where the toolchain makes them (GCC and Clang on
// ELF targets: the loader picks one through an indirect function); elsewhere the baseline alone.
#if defined(__GNUC__) && defined(__x86_64__) && defined(__ELF__)
#define POSEKIT_BLOCK_KERNEL __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define POSEKIT_BLOCK_KERNEL
#endif

// Nine dot products of three columns of t with three of g in one pass, into s(a, b) = t_a . g_b
// column-major; `omp simd reduction` lets the sums run in vector lanes (a reordering the compiler may
// not make on its own).
POSEKIT_BLOCK_KERNEL void column_products(const double* t0, const double* t1, const double* t2, const double* g0,
                                          const double* g1, const double* g2, std::ptrdiff_t n, double* s) {
  double s00 = 0, s01 = 0, s02 = 0, s10 = 0, s11 = 0, s12 = 0, s20 = 0, s21 = 0, s22 = 0;
#pragma omp simd reduction(+ : s00, s01, s02, s10, s11, s12, s20, s21, s22)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    s00 += t0[i] * g0[i];
    s01 += t0[i] * g1[i];
    s02 += t0[i] * g2[i];
    s10 += t1[i] * g0[i];
    s11 += t1[i] * g1[i];
    s12 += t1[i] * g2[i];
    s20 += t2[i] * g0[i];
    s21 += t2[i] * g1[i];
    s22 += t2[i] * g2[i];
  }
  s[0] = s00, s[1] = s10, s[2] = s20, s[3] = s01, s[4] = s11, s[5] = s21, s[6] = s02, s[7] = s12, s[8] = s22;
}

// o_c += g0 m(0, c) + g1 m(1, c) + g2 m(2, c) for c = 0..2; m is 3 by 3, column-major.
POSEKIT_BLOCK_KERNEL void column_sums(const double* g0, const double* g1, const double* g2, const double* m,
                                      std::ptrdiff_t n, double* o0, double* o1, double* o2) {
  const double m00 = m[0], m10 = m[1], m20 = m[2], m01 = m[3], m11 = m[4], m21 = m[5], m02 = m[6], m12 = m[7],
               m22 = m[8];
#pragma omp simd
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    o0[i] += g0[i] * m00 + g1[i] * m10 + g2[i] * m20;
    o1[i] += g0[i] * m01 + g1[i] * m11 + g2[i] * m21;
    o2[i] += g0[i] * m02 + g1[i] * m12 + g2[i] * m22;
  }
}

// L y = b, then L^T x = y, for three right sides; l is column-major with leading dimension ld. Forward
// by columns of L (updates of the rows below), backward by dot products with the same columns.
POSEKIT_BLOCK_KERNEL void triangular_solves(const double* l, std::ptrdiff_t n, std::ptrdiff_t ld, double* x0,
                                            double* x1, double* x2) {
  for (std::ptrdiff_t j = 0; j < n; ++j) {
    const double* column = l + j * ld;
    const double y0 = x0[j] /= column[j];
    const double y1 = x1[j] /= column[j];
    const double y2 = x2[j] /= column[j];
#pragma omp simd
    for (std::ptrdiff_t i = j + 1; i < n; ++i) {
      x0[i] -= column[i] * y0;
      x1[i] -= column[i] * y1;
      x2[i] -= column[i] * y2;
    }
  }
  for (std::ptrdiff_t j = n - 1; j >= 0; --j) {
    const double* column = l + j * ld;
    double s0 = 0, s1 = 0, s2 = 0;
#pragma omp simd reduction(+ : s0, s1, s2)
    for (std::ptrdiff_t i = j + 1; i < n; ++i) {
      s0 += column[i] * x0[i];
      s1 += column[i] * x1[i];
      s2 += column[i] * x2[i];
    }
    x0[j] = (x0[j] - s0) / column[j];
    x1[j] = (x1[j] - s1) / column[j];
    x2[j] = (x2[j] - s2) / column[j];
  }
}

// Rows per tile: few enough that a tile's six running sums stay in vector registers (AVX-512) or the
// first-level cache while the columns of both factors stream past.
constexpr std::ptrdiff_t kTileRows = 16;

// out_c[r] = sum_j s_j[r] sum_k a_k[r] maps(k, 3 j + c) for r < rows <= kTileRows; a_k, s_j are the
// columns of the two factors (strides lda, lds) and maps is column-major with leading dimension p.
POSEKIT_BLOCK_KERNEL void factored_tile(const double* a, std::ptrdiff_t lda, std::ptrdiff_t p, const double* s,
                                        std::ptrdiff_t lds, std::ptrdiff_t sums, const double* maps,
                                        std::ptrdiff_t rows, double* o0, double* o1, double* o2) {
  double t0[kTileRows] = {}, t1[kTileRows] = {}, t2[kTileRows] = {};
  for (std::ptrdiff_t j = 0; j < sums; ++j) {
    double m0[kTileRows] = {}, m1[kTileRows] = {}, m2[kTileRows] = {};
    const double* x = maps + 3 * j * p;
    for (std::ptrdiff_t k = 0; k < p; ++k) {
      const double* column = a + k * lda;
      const double c0 = x[k], c1 = x[p + k], c2 = x[2 * p + k];
#pragma omp simd
      for (std::ptrdiff_t r = 0; r < kTileRows; ++r) {
        const double value = r < rows ? column[r] : 0.0;
        m0[r] += value * c0;
        m1[r] += value * c1;
        m2[r] += value * c2;
      }
    }
    const double* factor = s + j * lds;
#pragma omp simd
    for (std::ptrdiff_t r = 0; r < kTileRows; ++r) {
      const double f = r < rows ? factor[r] : 0.0;
      t0[r] += f * m0[r];
      t1[r] += f * m1[r];
      t2[r] += f * m2[r];
    }
  }
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    o0[r] = t0[r];
    o1[r] = t1[r];
    o2[r] = t2[r];
  }
}

}  // namespace

void cholesky_solve(const Eigen::MatrixXd& factor, Eigen::Ref<Eigen::MatrixX3d> x) {
  eigen_assert(factor.rows() == factor.cols() && factor.rows() == x.rows());
  triangular_solves(factor.data(), factor.rows(), factor.outerStride(), x.col(0).data(), x.col(1).data(),
                    x.col(2).data());
}

void factored_block_product(const Eigen::Ref<const Eigen::MatrixXd>& multiplied,
                            const Eigen::Ref<const Eigen::MatrixXd>& summed, const Eigen::MatrixXd& maps,
                            Eigen::Ref<Eigen::MatrixX3d> out) {
  eigen_assert(maps.rows() == multiplied.cols() && maps.cols() == 3 * summed.cols());
  eigen_assert(multiplied.rows() == out.rows() && summed.rows() == out.rows());
  const std::ptrdiff_t rows = out.rows();
  for (std::ptrdiff_t first = 0; first < rows; first += kTileRows) {
    const std::ptrdiff_t height = std::min(kTileRows, rows - first);
    factored_tile(multiplied.data() + first, multiplied.outerStride(), multiplied.cols(), summed.data() + first,
                  summed.outerStride(), summed.cols(), maps.data(), height, out.col(0).data() + first,
                  out.col(1).data() + first, out.col(2).data() + first);
  }
}

Eigen::Matrix3d block_product(const Eigen::Ref<const Eigen::MatrixX3d>& t,
                              const Eigen::Ref<const Eigen::MatrixX3d>& block) {
  eigen_assert(t.rows() == block.rows());
  Eigen::Matrix3d product;
  column_products(t.col(0).data(), t.col(1).data(), t.col(2).data(), block.col(0).data(), block.col(1).data(),
                  block.col(2).data(), t.rows(), product.data());
  return product;
}

void accumulate_block(const Eigen::Ref<const Eigen::MatrixX3d>& block, const Eigen::Matrix3d& m,
                      Eigen::Ref<Eigen::MatrixX3d> side) {
  eigen_assert(block.rows() == side.rows());
  column_sums(block.col(0).data(), block.col(1).data(), block.col(2).data(), m.data(), block.rows(),
              side.col(0).data(), side.col(1).data(), side.col(2).data());
}

}  // namespace posekit::detail

// The loops of a blended deformation that stream its large arrays: the local step's products
// T^T G_j and the global step's sum of G_j R_j^T over the projected blocks G, the solve with the
// Cholesky factor, and the vertex evaluation's factored product. They are compiled for wider vector
// units as well and the widest copy the processor runs is taken at load time: the library itself is
// built for the architecture's baseline.
#pragma once

#include <Eigen/Core>

namespace posekit::detail {

/// s(a, b) = t.col(a) . block.col(b) for a, b in 0..2: T^T G_j for one block of G.
Eigen::Matrix3d block_product(const Eigen::Ref<const Eigen::MatrixX3d>& t,
                              const Eigen::Ref<const Eigen::MatrixX3d>& block);

/// side += block * m (rows by 3 times 3 by 3) for one block of G; the rows of `block` and `side` match.
void accumulate_block(const Eigen::Ref<const Eigen::MatrixX3d>& block, const Eigen::Matrix3d& m,
                      Eigen::Ref<Eigen::MatrixX3d> side);

/// x = (L L^T)^-1 x in place for the three columns of x together (one pass over L each way); `factor`
/// holds L in its lower triangle, as Eigen::LLT::matrixLLT() does.
void cholesky_solve(const Eigen::MatrixXd& factor, Eigen::Ref<Eigen::MatrixX3d> x);

/// out(i, c) = sum_j summed(i, j) sum_k multiplied(i, k) maps(k, 3 j + c): the dictionary's factored
/// product D T (DictionaryProduct) for the rows of one block, without forming multiplied * maps.
/// maps is multiplied.cols() by 3 summed.cols(); the rows of both factors and `out` match.
void factored_block_product(const Eigen::Ref<const Eigen::MatrixXd>& multiplied,
                            const Eigen::Ref<const Eigen::MatrixXd>& summed, const Eigen::MatrixXd& maps,
                            Eigen::Ref<Eigen::MatrixX3d> out);

}  // namespace posekit::detail

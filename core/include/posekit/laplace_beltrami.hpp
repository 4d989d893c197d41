// The discrete Laplace-Beltrami operator of a triangle mesh (cotangent stiffness and lumped mass) and
// its lowest eigenfunctions, which serve as smooth blending weights for example-based deformation.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace posekit {

/// Throws ArgumentError unless the #V by 3 `vertices` and #F by 3 `faces` make a mesh on which the
/// operator is defined: finite coordinates, valid indices, every vertex in some face, and no face whose
/// area is below 1e-12 of the mean face area. The message names the first offending face or vertex.
void check_laplace_beltrami_mesh(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// #V by #V cotangent Laplacian, positive semidefinite: L(i,j) = -(cot a_ij + cot b_ij) / 2 for each
/// edge ij (a_ij, b_ij the angles opposite it), L(i,i) = -sum_j L(i,j); x^T L x is the Dirichlet energy
/// of the piecewise-linear function x. Faces must be valid (check_laplace_beltrami_mesh).
Eigen::SparseMatrix<double> cotangent_laplacian(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// #V lumped (barycentric) masses: a third of the area of every face around each vertex.
Eigen::VectorXd lumped_mass(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                            const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// The lowest eigenpairs of L phi = lambda M phi (L cotangent Laplacian, M lumped mass).
struct LaplaceBeltramiBasis {
  Eigen::VectorXd eigenvalues;     ///< count values, ascending (the first is 0 up to round-off)
  Eigen::MatrixXd eigenfunctions;  ///< #V by count, M-orthonormal: Phi^T M Phi = I; sign fixed so that
                                   ///< each column's largest-magnitude entry is positive
};

/// The `count` eigenpairs of smallest eigenvalue of the mesh (#V by 3 `vertices`, #F by 3 `faces`),
/// found by Spectra in shift-invert mode around a small negative shift with one sparse LDLT
/// factorization. 1 <= count < #V; throws ArgumentError otherwise, for a degenerate mesh (see
/// check_laplace_beltrami_mesh), or when the eigensolver does not converge.
LaplaceBeltramiBasis laplace_beltrami_basis(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                            const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                            int count);

/// m by m smoothness of m blending weight functions (#V by m `weights`): S = (L W)^T M^-1 (L W), the
/// discrete integral of products of their Laplacians. For M-orthonormal eigenfunctions it is the
/// diagonal matrix of squared eigenvalues.
Eigen::MatrixXd weight_smoothness(const Eigen::SparseMatrix<double>& laplacian, const Eigen::VectorXd& mass,
                                  const Eigen::MatrixXd& weights);

}  // namespace posekit

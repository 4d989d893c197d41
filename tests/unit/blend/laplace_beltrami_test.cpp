#include <gtest/gtest.h>

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/laplace_beltrami.hpp>

#include "blend_test_shapes.hpp"
#include "test_data.hpp"

#include <Eigen/Eigenvalues>

namespace posekit {
namespace {

// A flat n by n grid of squares split into triangles, in the unit square.
Mesh flat_grid(int n) {
  Mesh mesh;
  mesh.vertices.resize((n + 1) * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) mesh.vertices.row(i * (n + 1) + j) << double(j) / n, double(i) / n, 0.0;
  }
  mesh.faces.resize(2 * n * n, 3);
  int f = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.faces.row(f++) << a, b, d;
      mesh.faces.row(f++) << a, d, c;
    }
  }
  return mesh;
}

TEST(CotangentLaplacian, IsSymmetricWithZeroRowSums) {
  const Mesh sphere = testing::icosphere(2);
  const Eigen::SparseMatrix<double> l = cotangent_laplacian(sphere.vertices, sphere.faces);
  const Eigen::MatrixXd dense = l;
  EXPECT_LT((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((dense * Eigen::VectorXd::Ones(dense.cols())).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-10);
}

TEST(CotangentLaplacian, DirichletEnergyOfALinearFunctionIsTheArea) {
  // On a flat mesh the piecewise-linear interpolant of f(x, y) = 2x + 3y is exact, |grad f|^2 = 13.
  const Mesh grid = flat_grid(6);
  const Eigen::SparseMatrix<double> l = cotangent_laplacian(grid.vertices, grid.faces);
  const Eigen::VectorXd f = 2.0 * grid.vertices.col(0) + 3.0 * grid.vertices.col(1);
  EXPECT_NEAR(f.dot(l * f), 13.0, 1e-10);
}

TEST(LumpedMass, SumsToTheArea) {
  const Mesh sphere = testing::icosphere(2);
  EXPECT_NEAR(lumped_mass(sphere.vertices, sphere.faces).sum(), face_areas(sphere.vertices, sphere.faces).sum(), 1e-12);
}

TEST(LaplaceBeltramiBasis, MatchesTheSpectrumOfTheSphere) {
  // The unit sphere: eigenvalues l (l + 1) with multiplicity 2 l + 1: 0, 2 (x3), 6 (x5).
  const Mesh sphere = testing::icosphere(3);
  const LaplaceBeltramiBasis basis = laplace_beltrami_basis(sphere.vertices, sphere.faces, 9);
  ASSERT_EQ(basis.eigenvalues.size(), 9);
  EXPECT_NEAR(basis.eigenvalues(0), 0.0, 1e-8);
  for (int j = 1; j <= 3; ++j) EXPECT_NEAR(basis.eigenvalues(j), 2.0, 0.02) << j;
  for (int j = 4; j <= 8; ++j) EXPECT_NEAR(basis.eigenvalues(j), 6.0, 0.08) << j;
  for (int j = 1; j < 9; ++j) EXPECT_GE(basis.eigenvalues(j), basis.eigenvalues(j - 1));
}

TEST(LaplaceBeltramiBasis, EigenfunctionsAreMassOrthonormalAndSolveTheProblem) {
  const PoseSet arm = testing::small_arm({0.0});
  const LaplaceBeltramiBasis basis = laplace_beltrami_basis(arm.pose(0), arm.faces(), 12);
  const Eigen::VectorXd mass = lumped_mass(arm.pose(0), arm.faces());
  const Eigen::SparseMatrix<double> l = cotangent_laplacian(arm.pose(0), arm.faces());
  const Eigen::MatrixXd& phi = basis.eigenfunctions;
  const Eigen::MatrixXd gram = phi.transpose() * mass.asDiagonal() * phi;
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(12, 12)).cwiseAbs().maxCoeff(), 1e-8);
  const Eigen::MatrixXd residual = l * phi - mass.asDiagonal() * phi * basis.eigenvalues.asDiagonal();
  EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-7 * (1.0 + basis.eigenvalues.maxCoeff()));
  // The first one is the constant function of unit mass norm, taken positive.
  EXPECT_LT((phi.col(0).array() - phi(0, 0)).abs().maxCoeff(), 1e-8);
  EXPECT_GT(phi(0, 0), 0.0);
}

TEST(WeightSmoothness, IsTheSquaredEigenvaluesForEigenfunctions) {
  const PoseSet arm = testing::small_arm({0.0});
  const LaplaceBeltramiBasis basis = laplace_beltrami_basis(arm.pose(0), arm.faces(), 8);
  const Eigen::MatrixXd s = weight_smoothness(cotangent_laplacian(arm.pose(0), arm.faces()),
                                              lumped_mass(arm.pose(0), arm.faces()), basis.eigenfunctions);
  const Eigen::MatrixXd expected = basis.eigenvalues.cwiseAbs2().asDiagonal();
  EXPECT_TRUE(testing::matrices_near(s, expected, 1e-6 * expected.maxCoeff(), 1e-6));
}

TEST(LaplaceBeltramiMesh, RejectsDegenerateFacesAndLooseVertices) {
  Mesh sphere = testing::icosphere(1);
  EXPECT_NO_THROW(check_laplace_beltrami_mesh(sphere.vertices, sphere.faces));
  Mesh flat = sphere;
  flat.vertices.row(flat.faces(3, 2)) = 0.5 * (flat.vertices.row(flat.faces(3, 0)) + flat.vertices.row(flat.faces(3, 1)));
  try {
    check_laplace_beltrami_mesh(flat.vertices, flat.faces);
    FAIL() << "a zero-area face was accepted";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("zero area"), std::string::npos) << error.what();
  }
  Mesh loose = sphere;
  loose.vertices.conservativeResize(loose.vertices.rows() + 1, 3);
  loose.vertices.bottomRows(1) << 2.0, 0.0, 0.0;
  EXPECT_THROW(check_laplace_beltrami_mesh(loose.vertices, loose.faces), ArgumentError);
  EXPECT_THROW(laplace_beltrami_basis(loose.vertices, loose.faces, 3), ArgumentError);
}

TEST(LaplaceBeltramiBasis, RejectsACountOutOfRange) {
  const Mesh sphere = testing::icosphere(1);
  EXPECT_THROW(laplace_beltrami_basis(sphere.vertices, sphere.faces, 0), ArgumentError);
  EXPECT_THROW(laplace_beltrami_basis(sphere.vertices, sphere.faces, static_cast<int>(sphere.vertices.rows())),
               ArgumentError);
}

}  // namespace
}  // namespace posekit

// As-rigid-as-possible deformation by CGAL's Surface_mesh_deformation (SRE_ARAP).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace posekit::detail {

/// Deforms the #V by 3 `rest` of the #F by 3 `faces`: each vertex with `held[v]` != 0 goes to row v
/// of `held_positions`, the others follow as rigidly as possible (local/global iterations up to
/// `iterations`, or until the energy changes by less than `energy_tolerance`, relatively). Returns
/// every vertex's position, or nothing where the faces do not make a manifold surface or the system
/// cannot be factored.
std::optional<Eigen::MatrixX3d> deform_as_rigid_as_possible(const Eigen::Ref<const Eigen::MatrixX3d>& rest,
                                                            const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                            const std::vector<char>& held,
                                                            const Eigen::Ref<const Eigen::MatrixX3d>& held_positions,
                                                            unsigned iterations, double energy_tolerance);

}  // namespace posekit::detail

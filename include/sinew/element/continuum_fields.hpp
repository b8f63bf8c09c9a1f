#pragma once
// Strain and stress fields of a deformed mesh, the ones a ParaView user expects: J, principal
// stretches, Green-Lagrange strain, Cauchy stress and von Mises stress. Per element each field
// is the volume-weighted mean of its pointwise value over the element's quadrature points (one
// point for a tetrahedron, 2x2x2 Gauss points for a hexahedron); per vertex it is the mean of the
// values of the elements around the vertex, weighted by their rest volumes.
#include <Eigen/Core>

#include "sinew/element/discretization.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

// Per element, flattened element by element (values[components * e + k]); tensors row-major.
struct ContinuumFields {
  Eigen::VectorXd J;                    // 1: det F
  Eigen::VectorXd principal_stretches;  // 3: singular values of F, largest first
  Eigen::VectorXd green_lagrange;       // 9: E = (F^T F - I) / 2
  // With a material only (empty otherwise). NaN where the material is undefined (an inverted
  // element of a J > 0 material) or J = 0.
  Eigen::VectorXd cauchy;     // 9: sigma = P F^T / J, P the first Piola-Kirchhoff stress
  Eigen::VectorXd von_mises;  // 1: sqrt(3/2 s:s), s = sigma - tr(sigma) I / 3
};

// The fields at positions x (x[3 v + i]); `material` may be null (kinematic fields only).
ContinuumFields continuum_fields(const Discretization& disc, const Material* material, const Eigen::VectorXd& x);

// Per-vertex values of an element field with `components` values per element: at vertex v,
// sum_e V_e f_e / sum_e V_e over the elements e that contain v, V_e the rest volume.
Eigen::VectorXd average_to_vertices(const Discretization& disc, const Eigen::VectorXd& element_values, int components);

// The pointwise quantities (also what the tests compare against).
Mat3 cauchy_stress(const Mat3& F, const Mat3& P);  // P F^T / det F
double von_mises_stress(const Mat3& sigma);
Vec3 principal_stretches(const Mat3& F);  // largest first

}  // namespace sinew

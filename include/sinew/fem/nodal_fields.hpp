#pragma once
// Element fields (J, stress, ...) carried to vertices and embedded points for surface output:
// renderers colour vertices, not elements.
#include <Eigen/Core>

#include "sinew/fem/discretization.hpp"
#include "sinew/fem/embedding.hpp"

namespace sinew {

// Per mesh vertex: the rest-volume-weighted mean of the values of the elements around it.
Eigen::VectorXd nodal_average(const Discretization& disc, const Eigen::VectorXd& per_element);

// Per embedded point: the nodal values interpolated with the point's shape-function weights.
Eigen::VectorXd interpolate_at_points(const Embedding& embedding, const Eigen::VectorXd& nodal);

}  // namespace sinew

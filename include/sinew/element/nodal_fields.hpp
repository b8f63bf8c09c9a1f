#pragma once
// Element fields (J, stress, ...) carried to vertices and embedded points for surface output:
// renderers colour vertices, not elements.
#include <Eigen/Core>

#include "sinew/element/discretization.hpp"
#include "sinew/element/embedding.hpp"

namespace sinew {

// Per mesh vertex: the rest-volume-weighted mean of the values of the elements around it,
// skipping non-finite values (a stress of an inverted element); a vertex with none gets 0.
Eigen::VectorXd nodal_average(const Discretization& disc, const Eigen::VectorXd& per_element);

// Per embedded point: the nodal values interpolated with the point's shape-function weights.
Eigen::VectorXd interpolate_at_points(const Embedding& embedding, const Eigen::VectorXd& nodal);

}  // namespace sinew

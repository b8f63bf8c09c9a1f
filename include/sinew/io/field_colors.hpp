#pragma once
// The colour scale of per-vertex fields in the viewer: a sequential map from indigo through
// blue, teal and green to yellow (lightness increases monotonically, so it reads in grey too).
// The glTF writer stores the table in the file, so the page colours frames with the same map.
#include <Eigen/Core>
#include <vector>

namespace sinew {

// The map's stops at evenly spaced positions 0..1, linear RGB (glTF's COLOR_0 space).
const std::vector<Eigen::Vector3f>& field_color_stops();

// Per-value colour: values clamped to [lo, hi], mapped to 0..1, linearly interpolated between
// stops. lo == hi maps every value to the middle of the scale.
Eigen::MatrixX3f field_colors(const Eigen::VectorXf& values, float lo, float hi);

}  // namespace sinew

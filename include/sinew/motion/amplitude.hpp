#pragma once
// A load or motion factor as a function of the (possibly fractional) frame number, as Abaqus'
// *AMPLITUDE and FEBio's load curves: piecewise linear through (frame, factor) points, held
// constant before the first point and after the last. No points means the constant 1 (a load
// applied in full from frame 1, Sinew's behaviour before amplitudes existed).
#include <string>
#include <utility>
#include <vector>

namespace sinew {

struct Amplitude {
  std::vector<std::pair<double, double>> points;  // (frame, factor), frames strictly increasing
  // Written "ramp" in a scene: 0 at frame 0 to 1 at the scene's last frame, which is known only
  // once the whole scene is read (then resolve_ramp sets the points).
  bool ramp_to_last_frame = false;
  void resolve_ramp(double last_frame) {
    if (ramp_to_last_frame) *this = ramp(last_frame);
  }

  static Amplitude constant() { return {}; }
  // Load control: 0 at frame 0 rising linearly to 1 at `last_frame`.
  static Amplitude ramp(double last_frame) { return {{{0.0, 0.0}, {last_frame, 1.0}}}; }

  double at(double frame) const;
  bool is_constant_one() const { return points.empty(); }
};

// Finite values, at least one point, frames strictly increasing; errors name `context`.
void validate_amplitude(const Amplitude& amplitude, const std::string& context);

}  // namespace sinew

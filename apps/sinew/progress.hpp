#pragma once
// Progress of `sinew run` on stderr (docs/scene-format.md, "Progress and exit codes"):
//   live   (a terminal): one line per frame, redrawn in place while the frame runs (Newton
//          iteration, residual, elapsed, ETA) and left as the frame's summary when it is done;
//   plain  (a pipe, a file, a CI log, or --progress=plain): the summary line per frame only;
//   quiet  (--quiet): nothing (errors and warnings are printed by the caller);
// --verbose adds one line per Newton iteration (SQP step for energy-limited dynamics).
#include <cstdio>
#include <string>

#include "sinew/run/simulation.hpp"

namespace sinew::cli {

enum class ProgressStyle { Live, Plain, Quiet };

// "auto" (live when `stream` is a terminal, else plain), "live" or "plain"; a sinew::Error
// naming --progress otherwise.
ProgressStyle progress_style(const std::string& choice, std::FILE* stream);

// A duration for people: "0.4 s", "12.3 s", "4 min 05 s", "2 h 03 min".
std::string format_duration(double seconds);

class ProgressPrinter {
 public:
  // `sqp`: the run's integrator reports SQP steps and PGS iterations instead of Newton and
  // linear iterations (energy-limited dynamics).
  ProgressPrinter(ProgressStyle style, bool verbose, bool sqp, std::FILE* stream = stderr);
  void operator()(const ProgressEvent& e);
  // Clears an unfinished live line, so that an error message starts on a clean line.
  void clear_line();

 private:
  // Remaining time from the mean duration of the frames finished in this run (not before a
  // resume); empty before the first one is done.
  std::string eta(const ProgressEvent& e) const;

  ProgressStyle style_;
  bool verbose_, sqp_;
  std::FILE* stream_;
  bool line_open_ = false;   // a live line is on screen without its newline
  int frames_done_ = 0;      // in this run
  double frames_seconds_ = 0.0;
  double frame_start_ = 0.0;  // elapsed time at the current frame's start
};

}  // namespace sinew::cli

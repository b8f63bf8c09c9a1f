#include "progress.hpp"

#include <cmath>
#include <fmt/format.h>
#include <unistd.h>

#include "sinew/core/error.hpp"

namespace sinew::cli {

ProgressStyle progress_style(const std::string& choice, std::FILE* stream) {
  if (choice == "auto") return isatty(fileno(stream)) ? ProgressStyle::Live : ProgressStyle::Plain;
  if (choice == "live") return ProgressStyle::Live;
  if (choice == "plain") return ProgressStyle::Plain;
  throw Error(fmt::format("expected auto, live or plain, got '{}'", choice), "--progress");
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  if (seconds < 59.95) return fmt::format("{:.1f} s", seconds);
  const long s = std::lround(seconds);
  if (s < 3600) return fmt::format("{} min {:02d} s", s / 60, s % 60);
  return fmt::format("{} h {:02d} min", s / 3600, (s % 3600) / 60);
}

ProgressPrinter::ProgressPrinter(ProgressStyle style, bool verbose, bool sqp, std::FILE* stream)
    : style_(style), verbose_(verbose), sqp_(sqp), stream_(stream) {}

std::string ProgressPrinter::eta(const ProgressEvent& e) const {
  if (frames_done_ == 0) return "";
  const int left = e.frames - e.frame + (e.frame_done ? 0 : 1);
  const double in_frame = e.frame_done ? 0.0 : e.elapsed - frame_start_;
  const double mean = frames_seconds_ / frames_done_;
  return format_duration(std::max(0.0, left * mean - in_frame));
}

void ProgressPrinter::clear_line() {
  if (line_open_) fmt::print(stream_, "\r\033[K");
  line_open_ = false;
  std::fflush(stream_);
}

void ProgressPrinter::operator()(const ProgressEvent& e) {
  if (style_ == ProgressStyle::Quiet) return;
  const char* outer_name = sqp_ ? "step" : "Newton";
  if (!e.frame_done) {
    if (e.newton_iteration == 0) frame_start_ = e.elapsed;
    if (verbose_ && e.newton_iteration > 0) {
      clear_line();
      fmt::print(stream_, "frame {}/{} {} {} residual {:.3e} elapsed {}\n", e.frame, e.frames, outer_name,
                 e.newton_iteration, e.residual, format_duration(e.elapsed));
    }
    if (style_ == ProgressStyle::Live) {
      const std::string left = eta(e);
      const std::string iterate =
          e.newton_iteration > 0 ? fmt::format("  {} {}  residual {:.3e}", outer_name, e.newton_iteration, e.residual) : "";
      fmt::print(stream_, "\r\033[Kframe {}/{}{}  elapsed {}{}", e.frame, e.frames, iterate, format_duration(e.elapsed),
                 left.empty() ? "" : "  ETA " + left);
      line_open_ = true;
      std::fflush(stream_);
    }
    return;
  }
  const FrameRecord& r = *e.record;
  ++frames_done_;
  frames_seconds_ += e.elapsed - frame_start_;
  clear_line();
  const double outer = sqp_ ? r.counter("sqp_iterations") : r.newton_iterations;
  const double inner = sqp_ ? r.counter("pgs_iterations") : r.linear_iterations;
  fmt::print(stream_, "frame {}/{}: {} {}, {} {} iterations, residual {:.3e}, volume {:.6g}, {:.2f} s, elapsed {}{}{}\n",
             e.frame, e.frames, outer, sqp_ ? "SQP" : "Newton", inner, sqp_ ? "PGS" : "linear", r.residual, r.volume,
             r.seconds, format_duration(e.elapsed), e.frame < e.frames ? ", ETA " + eta(e) : "",
             r.converged ? "" : "  NOT CONVERGED: " + r.failure);
  std::fflush(stream_);
}

}  // namespace sinew::cli

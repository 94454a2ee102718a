#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace sc {

Progress::Progress(std::string label, double end_time, Shown shown)
    : label_(std::move(label)), end_(end_time), shown_(shown == Shown::yes), tty_(::isatty(2) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

Progress::Progress(std::string label, long total, std::string unit)
    : Progress(std::move(label), static_cast<double>(total)) {
  unit_ = std::move(unit);
}

void Progress::update(double time, long steps) {
  const auto now = std::chrono::steady_clock::now();
  if (tty_) {
    if (now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    draw(time, steps, false);
    return;
  }
  const int decile = static_cast<int>(10.0 * time / end_);
  if (decile > last_decile_) {
    last_decile_ = decile;
    draw(time, steps, false);
  }
}

void Progress::done(double time, long steps) { draw(time, steps, true); }

void Progress::draw(double time, long steps, bool final) {
  if (!shown_) return;
  const double fraction = std::min(1.0, time / end_);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  char where[64];
  if (unit_.empty()) std::snprintf(where, sizeof where, "t=%.4f s  %ld steps", time, steps);
  else std::snprintf(where, sizeof where, "%ld of %.0f %s", steps, end_, unit_.c_str());
  if (tty_) {
    const int width = 30, filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r%-22s [%.*s%*s] %3.0f%%  %s  %.1f s (eta %.0f s)%s", label_.c_str(), filled,
                 "##############################", width - filled, "", 100.0 * fraction, where, elapsed, eta,
                 final ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s: %3.0f%%  %s  %.1f s%s\n", label_.c_str(), 100.0 * fraction, where, elapsed,
                 final ? "  done" : "");
  }
  std::fflush(stderr);
}

}  // namespace sc

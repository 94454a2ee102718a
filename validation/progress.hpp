// Progress of a long run, or of a count of items (`sandcastle render`'s frames): a bar redrawn in
// place on a terminal, a line every 10 % otherwise. Over MPI ranks, one rank shows it (the others
// keep their stderr for errors).
#pragma once
#include <chrono>
#include <string>

namespace sc {

class Progress {
 public:
  /// Drawn, or not (a rank other than 0 of a decomposed run).
  enum class Shown { yes, no };
  Progress(std::string label, double end_time, Shown shown = Shown::yes);
  /// Counts `total` items named `unit` ("frames"): update(done, done) after each.
  Progress(std::string label, long total, std::string unit);
  void update(double time, long steps);
  void done(double time, long steps);

 private:
  void draw(double time, long steps, bool final);
  std::string label_;
  double end_;
  std::string unit_;  ///< empty: a run, drawn as time and steps
  bool shown_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace sc

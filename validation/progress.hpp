// Progress of a long run: a bar redrawn in place on a terminal, a line every 10 % otherwise.
#pragma once
#include <chrono>
#include <string>

namespace sc {

class Progress {
 public:
  Progress(std::string label, double end_time);
  void update(double time, long steps);
  void done(double time, long steps);

 private:
  void draw(double time, long steps, bool final);
  std::string label_;
  double end_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace sc

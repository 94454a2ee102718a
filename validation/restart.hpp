// Checkpoint and restart of a run (`sandcastle run --checkpoint-every N`, `--resume FILE`): where a
// run starts (the case's scene, or a checkpoint), and the checkpoint of a run's current state with
// the frames it has written, so a resumed run continues the same frame series.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "case/case_file.hpp"
#include "method/method.hpp"

namespace sc {

/// The VTU frames a run has written, (time, file name), and the time of the last frame interval.
struct FrameLog {
  std::vector<std::pair<double, std::string>> frames;
  double next_frame = 0.0;
};

/// The method a run starts with, built by the registry (method/registry.hpp): the case's scene at
/// t = 0 or, when `resume_from` names a checkpoint, its state and frame log. The checkpoint must
/// come from the same case (parameters hash), dimension and spacing; otherwise, or if it is
/// unreadable, throws InputError. `decompose`: the scene is decomposed over the MPI ranks
/// (make_method), whatever number of ranks wrote the checkpoint.
template <int D>
std::unique_ptr<Method<D>> start_method(const CaseSpec& spec, double dx, const std::string& resume_from, FrameLog& log,
                                        bool decompose = false);

/// Writes the checkpoint of `method` and its frame log to `path` (atomically).
template <int D>
void write_run_checkpoint(const std::string& path, const Method<D>& method, const FrameLog& log);

/// File name of the checkpoint written after `step`: checkpoint_<step, 8 digits>.ckpt.
std::string checkpoint_name(long step);

}  // namespace sc

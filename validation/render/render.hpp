// `sandcastle render RUN_DIR --out DIR`: pictures of a run's frames (docs/render.md). 3-D runs: the
// surfaces of `run --surface` as POV-Ray scenes (render/pov_scene.hpp), rendered by Debian's
// povray and stored as PNG by ffmpeg (which drops POV-Ray's time stamp, so a frame renders to the
// same bytes every time). 2-D runs: particle snapshots drawn by reports/particle_snapshots.py
// (matplotlib, as the report's plots). Optionally a filmstrip of chosen frames side by side and an
// MP4 video, both made by ffmpeg. Checked by tests/test_render.cpp.
#pragma once
#include <string>
#include <vector>

namespace sc::render {

struct RenderOptions {
  std::string run_dir, out_dir;
  std::string case_file;          ///< empty: cases/<name>/case.json of the case named in RUN_DIR/series.json
  bool filmstrip = false;         ///< write DIR/filmstrip.png
  std::vector<long> frames;       ///< the filmstrip's frames; empty: the case's render.filmstrip, else first, middle, last
  bool video = false;             ///< write DIR/video.mp4
  bool strip_only = false;        ///< draw only the filmstrip's frames (with `filmstrip`; the report's pictures)
  int jobs = 2;                   ///< frames rendered at a time
};

/// The programs a render of a `dimension`-D run needs that are not on PATH (povray for 3-D; ffmpeg for
/// 3-D, filmstrips and videos), as a sentence naming them and their Debian packages; empty when all
/// are there. The 2-D particle snapshots need python3-matplotlib, which only drawing finds out.
std::string missing_programs(int dimension, bool filmstrip_or_video);

/// Renders the run: DIR/frame_NNNNN.png per frame (only the filmstrip's with `strip_only`; 3-D: by
/// way of the scene frame_NNNNN.pov), then the filmstrip and the video when asked. Returns the exit code: 0, 2 for bad input (InputError
/// thrown before anything is written), 4 when a program it needs is missing or fails.
int render_run(const RenderOptions& options);

}  // namespace sc::render

#include "render/render.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>

#include "case/case_file.hpp"
#include "data_root.hpp"
#include "io/atomic_file.hpp"
#include "io/json_reader.hpp"
#include "progress.hpp"
#include "render/frame_series.hpp"
#include "render/pov_scene.hpp"
#include "render/programs.hpp"
#include "render/render_settings.hpp"
#include "report_scripts.hpp"
#include "runner.hpp"

namespace fs = std::filesystem;

namespace sc::render {

namespace {

constexpr int kVideoFramesPerSecond = 10;

/// DIR/frame_NNNNN<ext>: the picture (and scene, log) of frame k.
std::string frame_file(const std::string& dir, std::size_t k, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%05zu%s", k, ext);
  return dir + name;
}

/// --case, else cases/<name>/case.json of the case RUN_DIR/series.json names.
std::string case_of_run(const RenderOptions& o) {
  if (!o.case_file.empty()) return o.case_file;
  const std::string series = o.run_dir + "/series.json";
  if (!fs::exists(series))
    throw InputError(series, "(document)", "missing: the run did not finish; name its case file with --case");
  const json document = read_json_file(series);
  JsonObject doc(document, "", series);
  const std::string name = doc.string("case");
  const std::string path = data_path("cases/" + name + "/case.json");
  if (!fs::exists(path)) throw InputError(series, "/case", "case " + name + " is not under cases/; name its case file with --case");
  return path;
}

/// The filmstrip's frames: those asked for (each one the run has), else the case's render.filmstrip
/// (those the run has: a quick run is shorter than the thesis' figure), else the first, middle and last.
std::vector<std::size_t> filmstrip_frames(const RenderOptions& o, const RenderSettings& s, std::size_t count) {
  std::vector<std::size_t> frames;
  for (const long f : o.frames) {
    if (static_cast<std::size_t>(f) >= count)
      throw InputError(o.run_dir + "/frames.pvd", "(--filmstrip)",
                       "frame " + std::to_string(f) + ": the run has frames 0 to " + std::to_string(count - 1));
    frames.push_back(static_cast<std::size_t>(f));
  }
  if (frames.empty() && !s.filmstrip.empty()) {
    for (const long f : s.filmstrip)
      if (static_cast<std::size_t>(f) < count) frames.push_back(static_cast<std::size_t>(f));
    if (frames.size() < s.filmstrip.size())
      std::cerr << "note: the frames of the case's render.filmstrip after frame " << count - 1
                << " are left out: the run has no more\n";
  }
  if (frames.empty())
    for (const std::size_t f : {std::size_t{0}, (count - 1) / 2, count - 1})
      if (frames.empty() || frames.back() != f) frames.push_back(f);
  return frames;
}

/// A 3-D run is drawn from its surfaces: every frame must have one.
void require_surfaces(const RenderOptions& o, const std::vector<Frame>& frames) {
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (frames[k].surfaces.empty())
      throw InputError(o.run_dir + "/frames.pvd", "",
                       "frame " + std::to_string(k) + " has no surfaces: run the 3-D case with --surface");
}

/// The programs the render needs, each found on PATH; the message naming those missing, if any.
std::string find_programs(int dimension, bool filmstrip_or_video, std::string& povray, std::string& ffmpeg) {
  povray = find_program("povray");
  ffmpeg = find_program("ffmpeg");
  std::string missing;
  if (dimension == 3 && povray.empty()) missing += " povray";
  if ((dimension == 3 || filmstrip_or_video) && ffmpeg.empty()) missing += " ffmpeg";
  if (missing.empty()) return missing;
  return "not found on PATH:" + missing + " (Debian: apt-get install" + missing + "; tools/install_deps.sh installs them)";
}

/// Frame k's scene: the surfaces of the run's frame, written to DIR/frame_NNNNN.pov.
void write_scene(const RenderOptions& o, const RenderSettings& s, const Frame& frame, std::size_t k) {
  std::vector<std::pair<Phase, surface::SurfaceMesh>> surfaces;
  for (const auto& [phase, file] : frame.surfaces) surfaces.emplace_back(phase, read_surface_file(o.run_dir + "/" + file));
  write_file_atomic(frame_file(o.out_dir, k, ".pov"), pov_scene(s, surfaces));
}

/// POV-Ray renders the scene to PPM without jitter (+A0.1 +AM2 -J: deterministic antialiasing) on
/// one thread, then ffmpeg stores it as PNG without POV-Ray's time stamp; the scene and the log are
/// removed when both succeed, kept when not (a scene is about the size of the run's surface files).
bool render_scene(const std::string& povray, const std::string& ffmpeg, const RenderSettings& s, const std::string& dir,
                  std::size_t k) {
  const std::string pov = frame_file(dir, k, ".pov"), ppm = frame_file(dir, k, ".ppm"), log = frame_file(dir, k, ".log");
  const bool ok = run_program({povray, "+I" + pov, "+O" + ppm, "+FP", "+W" + std::to_string(s.width),
                               "+H" + std::to_string(s.height), "-D", "-P", "+A0.1", "+AM2", "+R3", "-J", "+WT1"},
                              log) &&
                  run_program({ffmpeg, "-nostdin", "-v", "error", "-y", "-i", ppm, frame_file(dir, k, ".png")}, log);
  fs::remove(ppm);
  if (ok) {
    fs::remove(pov);
    fs::remove(log);
  }
  return ok;
}

/// 3-D: the chosen frames' surfaces, each a POV-Ray scene rendered to PNG.
bool render_surfaces(const RenderOptions& o, const RenderSettings& s, const std::vector<Frame>& frames,
                     const std::vector<std::size_t>& chosen, const std::string& povray, const std::string& ffmpeg) {
  for (const std::size_t k : chosen) write_scene(o, s, frames[k], k);
  Progress progress("render", static_cast<long>(chosen.size()), "frames");
  long finished = 0;
  const bool ok = run_parallel(
      chosen.size(), o.jobs, [&](std::size_t i) { return render_scene(povray, ffmpeg, s, o.out_dir, chosen[i]); },
      [&](std::size_t i, bool frame_ok) {
        if (!frame_ok)
          std::cerr << "\npovray or ffmpeg failed on frame " << chosen[i] << ": see "
                    << frame_file(o.out_dir, chosen[i], ".log") << "\n";
        ++finished;
        progress.update(static_cast<double>(finished), finished);
      });
  progress.done(static_cast<double>(finished), finished);
  return ok;
}

/// 2-D: reports/particle_snapshots.py draws the chosen frames' particles in the scene's box.
bool render_particles(const RenderOptions& o, const RenderSettings& s, const std::vector<Frame>& frames,
                      const std::vector<std::size_t>& chosen) {
  std::vector<std::string> args = {std::to_string(s.width), std::to_string(s.height)};
  for (const double v : {s.box_min[0], s.box_max[0], s.box_min[1], s.box_max[1]}) args.push_back(json(v).dump());
  for (const std::size_t k : chosen) {
    args.push_back(json(frames[k].time).dump());
    args.push_back(o.run_dir + "/" + frames[k].particles);
    args.push_back(frame_file(o.out_dir, k, ".png"));
  }
  return run_report_script("particle_snapshots.py", args);
}

/// Runs a program; removes its log when it succeeds, names it on stderr when it fails.
bool run_logged(const std::vector<std::string>& argv, const std::string& log) {
  if (run_program(argv, log)) {
    fs::remove(log);
    return true;
  }
  std::cerr << "error: " << argv[0] << " failed: see " << log << "\n";
  return false;
}

/// DIR/filmstrip.png: the frames side by side (ffmpeg's hstack filter).
bool write_filmstrip(const std::string& ffmpeg, const std::string& dir, const std::vector<std::size_t>& frames) {
  const std::string out = dir + "/filmstrip.png";
  if (frames.size() == 1) return fs::copy_file(frame_file(dir, frames[0], ".png"), out, fs::copy_options::overwrite_existing);
  std::vector<std::string> args = {ffmpeg, "-nostdin", "-v", "error", "-y"};
  for (const std::size_t k : frames) args.insert(args.end(), {"-i", frame_file(dir, k, ".png")});
  args.insert(args.end(), {"-filter_complex", "hstack=inputs=" + std::to_string(frames.size()), out});
  return run_logged(args, dir + "/filmstrip.log");
}

/// DIR/video.mp4: every frame in order, H.264 (even image sizes, as yuv420p needs).
bool write_video(const std::string& ffmpeg, const std::string& dir) {
  return run_logged({ffmpeg, "-nostdin", "-v", "error", "-y", "-framerate", std::to_string(kVideoFramesPerSecond),
                      "-start_number", "0", "-i", dir + "/frame_%05d.png", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                      "-c:v", "libx264", "-pix_fmt", "yuv420p", dir + "/video.mp4"},
                     dir + "/video.log");
}

}  // namespace

std::string missing_programs(int dimension, bool filmstrip_or_video) {
  std::string povray, ffmpeg;
  return find_programs(dimension, filmstrip_or_video, povray, ffmpeg);
}

int render_run(const RenderOptions& o) {
  const CaseSpec spec = load_case(case_of_run(o));
  const RenderSettings settings = read_render_settings(spec);
  const std::vector<Frame> frames = read_frame_series(o.run_dir);
  const std::vector<std::size_t> strip =
      o.filmstrip ? filmstrip_frames(o, settings, frames.size()) : std::vector<std::size_t>{};
  if (spec.dimension == 3) require_surfaces(o, frames);
  std::string povray, ffmpeg;
  if (const std::string missing = find_programs(spec.dimension, o.filmstrip || o.video, povray, ffmpeg); !missing.empty()) {
    std::cerr << "error: sandcastle render needs programs that are " << missing << "\n";
    return kToolMissing;
  }
  std::vector<std::size_t> chosen = strip;  // the frames to draw: the filmstrip's, or all of them
  if (!(o.filmstrip && o.strip_only)) {
    chosen.resize(frames.size());
    std::iota(chosen.begin(), chosen.end(), std::size_t{0});
  }
  fs::create_directories(o.out_dir);
  const bool drawn = spec.dimension == 3 ? render_surfaces(o, settings, frames, chosen, povray, ffmpeg)
                                         : render_particles(o, settings, frames, chosen);
  if (!drawn) return kToolMissing;
  std::cout << "frames: " << frames.size() << " pictures " << o.out_dir << "/frame_NNNNN.png\n";
  if (o.filmstrip) {
    if (!write_filmstrip(ffmpeg, o.out_dir, strip)) return kToolMissing;
    std::cout << "filmstrip: " << o.out_dir << "/filmstrip.png (frames";
    for (const std::size_t k : strip) std::cout << ' ' << k;
    std::cout << ")\n";
  }
  if (o.video) {
    if (!write_video(ffmpeg, o.out_dir)) return kToolMissing;
    std::cout << "video: " << o.out_dir << "/video.mp4\n";
  }
  return kSuccess;
}

}  // namespace sc::render

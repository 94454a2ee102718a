// `sandcastle render` (validation/render/, docs/render.md), run as the real command: a sphere seen
// by an orthographic camera covers exactly its projected disc in the PNG, and the same frame
// renders to the same bytes twice. Both need Debian's povray and ffmpeg and are skipped, saying so,
// without povray. The render block does not enter the parameters hash (baselines stay comparable).
#include <png.h>

#include <boost/test/unit_test.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "case/case_file.hpp"
#include "io/atomic_file.hpp"
#include "io/json_reader.hpp"
#include "io/vtu_writer.hpp"
#include "render/programs.hpp"
#include "runner.hpp"
#include "support/process.hpp"
#include "surface/surface_mesh.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

constexpr int kWidth = 480, kHeight = 360;  // not square: a camera that ignores the aspect shows
constexpr double kViewWidth = 2.0;         // the view [m]: 240 pixels per metre
constexpr double kRadius = 0.5;            // [m]

/// A UV sphere of `rings` latitude bands and 2·rings longitudes, triangles counter-clockwise from
/// outside; point k's saturation rises from 0 at the bottom to 1 at the top.
surface::SurfaceMesh uv_sphere(double r, int rings) {
  surface::SurfaceMesh m;
  const int segments = 2 * rings;
  m.points.push_back(Vec<3>(0, 0, -r));
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = pi * i / rings - pi / 2, phi = 2 * pi * j / segments;
      m.points.push_back(r * Vec<3>(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta)));
    }
  m.points.push_back(Vec<3>(0, 0, r));
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  const auto top = static_cast<std::uint32_t>(m.points.size() - 1);
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({0, at(1, j + 1), at(1, j)});
    m.triangles.push_back({top, at(rings - 1, j), at(rings - 1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  for (const Vec<3>& p : m.points) m.saturation.push_back(0.5 + 0.5 * p[2] / r);
  return m;
}

/// A run folder with one frame: the sphere as its sand surface (frames.pvd, the VTU, the VTP).
std::string sphere_run() {
  const std::string dir = test::fresh_path("render_run");
  fs::create_directories(dir);
  const std::vector<Vec<3>> centre = {Vec<3>::Zero()};
  write_file_atomic(dir + "/frame_00000.vtu", vtu_points_document<3>(centre, [](auto&&) {}));
  write_file_atomic(dir + "/" + surface_file_name(Phase::Sand, 0), surface::vtp_document(uv_sphere(kRadius, 128)));
  write_file_atomic(dir + "/frames.pvd", pvd_document({{0.0, "frame_00000.vtu"}}, [](std::size_t k) {
                      return std::vector<std::string>{surface_file_name(Phase::Sand, k)};
                    }));
  return dir;
}

/// A 3-D case whose render block looks at the origin along +y with an orthographic camera, lit from
/// the camera, on white without a floor.
json sphere_case() {
  return json::parse(R"({"name": "render_sphere", "dimension": 3,
    "domain": {"min": [-1, -1, -1], "max": [1, 1, 1]}, "gravity": [0, 0, -9.81], "time": {"end": 0.1},
    "water": {"rest_density": 1000, "sound_speed": 10},
    "blocks": [{"phase": "water", "min": [0, 0, 0], "max": [0.2, 0.2, 0.2]}],
    "tiers": {"quick": {"spacings": [0.05]}, "full": {"spacings": [0.05]}},
    "render": {"width": 480, "height": 360, "floor": false, "background": [1, 1, 1],
               "camera": {"projection": "orthographic", "location": [0, -5, 0], "look_at": [0, 0, 0], "view_width": 2.0},
               "lights": [{"position": [0, -20, 0]}]}})");
}

std::string write_case(const json& doc) {
  const std::string path = test::fresh_path("render_case", ".json");
  write_file_atomic(path, doc.dump(1));
  return path;
}

/// `sandcastle render RUN --case CASE --out OUT`; returns OUT/frame_00000.png.
std::string render_frame(const std::string& run, const std::string& case_file) {
  const std::string out = test::fresh_path("render_out");
  const test::ProcessResult r = test::run_sandcastle({"render", run, "--case", case_file, "--out", out}, 120.0);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  return out + "/frame_00000.png";
}

/// The pixels of a PNG as RGB bytes (libpng's simplified reader).
std::vector<unsigned char> rgb_pixels(const std::string& path, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  BOOST_TEST_REQUIRE(png_image_begin_read_from_file(&image, path.c_str()) != 0, path);
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  BOOST_TEST_REQUIRE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr) != 0, path);
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return pixels;
}

/// A 2-D resting tank of water, 0.06 m by 0.1 m at spacing 0.01, 0.05 s with a frame every
/// 0.01 s (six frames), drawn 160 × 120; in cases_dir/tank/case.json.
void write_tank_case(const std::string& cases_dir) {
  fs::create_directories(cases_dir + "/tank");
  write_file_atomic(cases_dir + "/tank/case.json", json::parse(R"({
    "name": "tank", "dimension": 2,
    "domain": {"min": [-0.05, -0.05], "max": [0.11, 0.21]}, "gravity": [0.0, -9.81],
    "time": {"end": 0.05, "dt": 0.001, "frame_interval": 0.01}, "support_ratio": 2.0,
    "water": {"rest_density": 1000.0, "sound_speed": 20.0, "viscosity": 1.0},
    "blocks": [{"phase": "water", "min": [0.0, 0.0], "max": [0.06, 0.1]}],
    "tank": {"min": [0.0, 0.0], "max": [0.06, 0.16], "sides": {"x-": "no_slip", "x+": "no_slip", "y-": "no_slip", "y+": "open"}},
    "validation": {"observer": "hydrostatic", "average_time": 0.02,
                   "metrics": {"pressure_l2": {"max": 10.0}, "surface_drift": {"max": 10.0}, "spurious_speed": {"max": 10.0}}},
    "tiers": {"quick": {"spacings": [0.01]}, "full": {"spacings": [0.01]}},
    "render": {"width": 160, "height": 120}})").dump(1));
}

/// `sandcastle validate --tier quick` of the tank case in a fresh folder, with `extra` arguments and
/// environment; the run's report.json (its exit code must be 0).
json validate_tank(const std::vector<std::string>& extra, const std::vector<std::string>& env, std::string& out) {
  const std::string root = test::fresh_path("filmstrip");
  write_tank_case(root + "/cases");
  out = root + "/run";
  std::vector<std::string> args = {"validate", "--tier", "quick", "--cases-dir", root + "/cases", "--baselines-dir",
                                   root + "/baselines", "--out", out};
  args.insert(args.end(), extra.begin(), extra.end());
  const test::ProcessResult r = test::run_sandcastle(args, 300.0, env);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  return read_json_file(out + "/report.json").at("cases").at(0);
}

struct PovrayPresent {
  boost::test_tools::assertion_result operator()(boost::unit_test::test_unit_id) const {
    boost::test_tools::assertion_result present(!render::find_program("povray").empty());
    present.message() << "povray is not installed (apt-get install povray, tools/install_deps.sh): render checks skipped";
    return present;
  }
};

struct FfmpegPresent {
  boost::test_tools::assertion_result operator()(boost::unit_test::test_unit_id) const {
    boost::test_tools::assertion_result present(!render::find_program("ffmpeg").empty());
    present.message() << "ffmpeg is not installed (apt-get install ffmpeg, tools/install_deps.sh): filmstrip check skipped";
    return present;
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(render)

// Orthographic projection maps a sphere of radius r to a disc of area π r² (240 px/m here), so
// the pixels that differ from the white background count that area within 2 % (edge pixels count
// when more than about half covered). Fails when the camera's view extent or its aspect is wrong,
// or vertices are written scaled or moved.
BOOST_AUTO_TEST_CASE(sphere_silhouette_is_the_projected_disc, *boost::unit_test::precondition(PovrayPresent())) {
  int width = 0, height = 0;
  const std::vector<unsigned char> px = rgb_pixels(render_frame(sphere_run(), write_case(sphere_case())), width, height);
  BOOST_TEST_REQUIRE(width == kWidth);
  BOOST_TEST_REQUIRE(height == kHeight);
  long covered = 0;
  for (std::size_t i = 0; i < px.size(); i += 3)
    covered += std::max({255 - px[i], 255 - px[i + 1], 255 - px[i + 2]}) > 64 ? 1 : 0;
  const double pixels_per_metre = kWidth / kViewWidth;
  const double disc = pi * std::pow(kRadius * pixels_per_metre, 2);
  BOOST_TEST(std::abs(covered - disc) / disc < 0.02, "covered " << covered << " pixels, disc " << disc);
}

// POV-Ray stamps its PNG and PPM output with the time; render stores the pixels through ffmpeg
// without it, and antialiasing without jitter, so a frame rendered twice, more than a second
// apart, is the same file byte for byte. Fails when POV-Ray's own PNG is kept.
BOOST_AUTO_TEST_CASE(same_frame_renders_to_the_same_bytes, *boost::unit_test::precondition(PovrayPresent())) {
  const std::string run = sphere_run(), case_file = write_case(sphere_case());
  const std::string first = test::read_text(render_frame(run, case_file));
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const std::string second = test::read_text(render_frame(run, case_file));
  BOOST_TEST_REQUIRE(!first.empty());
  BOOST_TEST((first == second), "the two renders differ");
}

// How a run is drawn is no parameter of it: a case with and without its render block hashes alike.
BOOST_AUTO_TEST_CASE(render_block_is_not_a_parameter) {
  json without = sphere_case();
  without.erase("render");
  BOOST_TEST(load_case(sphere_case(), "with.json").parameters_hash == load_case(without, "without.json").parameters_hash);
}

// The validation report shows every case: `validate` draws each observable's plot (PNG files named
// in report.json's "plots") and report.html with those plots embedded; it writes the finest run's
// frames and draws its first, middle and last frame side by side into <case>/pictures/filmstrip.png
// (three 160 px wide frames: 480 × 120), named in report.json; --no-pictures writes neither frames
// nor filmstrip; with no ffmpeg on PATH the case says why in filmstrip_note and its status is
// unchanged. Fails when a plot, the page or the filmstrip is not drawn, the filmstrip is drawn from
// other frames than the strip's, or its absence is silent. (CTest's validate.quick runs the quick
// tier with --no-plots; this is where the drawing path is checked.)
BOOST_AUTO_TEST_CASE(validate_draws_plots_and_a_filmstrip_of_each_case, *boost::unit_test::precondition(FfmpegPresent())) {
  std::string out;
  const json drawn = validate_tank({}, {"OMP_NUM_THREADS=1"}, out);
  BOOST_TEST_REQUIRE(!drawn.at("plots").empty(), drawn.dump());
  for (const auto& plot : drawn.at("plots")) {
    int w = 0, h = 0;
    rgb_pixels(out + "/" + plot.get<std::string>(), w, h);
    BOOST_TEST((w > 0 && h > 0), plot);
  }
  BOOST_TEST(test::read_text(out + "/report.html").find("data:image/png;base64,") != std::string::npos);
  BOOST_TEST_REQUIRE(drawn.contains("filmstrip"), drawn.dump());
  BOOST_TEST(drawn.at("filmstrip") == "tank/pictures/filmstrip.png");
  int width = 0, height = 0;
  rgb_pixels(out + "/" + drawn.at("filmstrip").get<std::string>(), width, height);
  BOOST_TEST(width == 3 * 160);
  BOOST_TEST(height == 120);
  BOOST_TEST(fs::exists(out + "/tank/frames.pvd"));
  BOOST_TEST(!fs::exists(out + "/tank/pictures/frame_00001.png"));  // only the strip's frames: 0, 2, 5
  BOOST_TEST(fs::exists(out + "/tank/pictures/frame_00002.png"));
  BOOST_TEST(test::read_text(out + "/summary.md").find("](tank/pictures/filmstrip.png)") != std::string::npos);

  const json skipped = validate_tank({"--no-pictures"}, {"OMP_NUM_THREADS=1"}, out);
  BOOST_TEST(!skipped.contains("filmstrip"));
  BOOST_TEST(!skipped.contains("filmstrip_note"));
  BOOST_TEST(!fs::exists(out + "/tank/frames.pvd"));
  BOOST_TEST(skipped.at("state_checksum") == drawn.at("state_checksum"));

  const std::string empty = test::fresh_path("empty_path");
  fs::create_directories(empty);
  const json missing = validate_tank({}, {"OMP_NUM_THREADS=1", "PATH=" + empty}, out);
  BOOST_TEST(!missing.contains("filmstrip"));
  BOOST_TEST(missing.value("filmstrip_note", "").find("ffmpeg") != std::string::npos, missing.dump());
  BOOST_TEST(missing.at("status") == drawn.at("status"));
}

BOOST_AUTO_TEST_SUITE_END()

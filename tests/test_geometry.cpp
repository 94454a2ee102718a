// Meshes: OBJ loading and its errors, the winding-number inside test, sampling, placement.
#include <boost/test/unit_test.hpp>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/errors.hpp"
#include "geometry/winding_number.hpp"
#include "support/process.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

TriangleMesh unit_cube() {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  // Two outward triangles per face.
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

/// A sphere of radius r: an octahedron subdivided `levels` times, vertices pushed to the sphere.
TriangleMesh sphere(double r, int levels) {
  TriangleMesh m;
  m.vertices = {Vec<3>(1, 0, 0), Vec<3>(-1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0, -1, 0), Vec<3>(0, 0, 1), Vec<3>(0, 0, -1)};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (!middle.count(key)) {
        middle[key] = static_cast<std::uint32_t>(m.vertices.size());
        m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      }
      return middle[key];
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& t : m.triangles) {
      const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    m.triangles = finer;
  }
  for (Vec<3>& v : m.vertices) v *= r;
  return m;
}

std::string write_obj(const std::string& name, const std::string& text) {
  const std::string path = test::fresh_path("mesh_" + name, ".obj");
  std::ofstream(path) << text;
  return path;
}

std::string obj_text(const TriangleMesh& m) {
  std::string s;
  for (const Vec<3>& v : m.vertices) s += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  for (const auto& t : m.triangles)
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return s;
}

bool throws_input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError&) {
    return true;
  }
  return false;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(geometry)

BOOST_AUTO_TEST_CASE(winding_number_of_unit_cube) {
  const TriangleMesh cube = unit_cube();
  BOOST_TEST(cube.signed_volume() == 1.0, boost::test_tools::tolerance(1e-12));
  const WindingNumber w(cube);
  BOOST_TEST(w(Vec<3>(0.5, 0.5, 0.5)) == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(w(Vec<3>(0.01, 0.99, 0.5)) == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::abs(w(Vec<3>(1.01, 0.5, 0.5))) < 1e-9);
  BOOST_TEST(std::abs(w(Vec<3>(-3.0, 2.0, 7.0))) < 1e-9);
  BOOST_TEST(!w.inside(Vec<3>(0.5, 0.5, -0.01)));
}

BOOST_AUTO_TEST_CASE(hierarchical_winding_number_separates_inside_and_outside_of_a_sphere) {
  const TriangleMesh s = sphere(1.0, 5);  // 8192 triangles: the far-field clusters are used
  const WindingNumber w(s);
  // The far-field (dipole) sums are accurate to about 1 %; the inside test only needs |w| vs 1/2.
  for (double r : {0.0, 0.3, 0.9, 0.98})
    BOOST_TEST(w(Vec<3>(r, 0.0, 0.0)) == 1.0, boost::test_tools::tolerance(0.02));
  for (double r : {1.02, 1.5, 10.0})
    BOOST_TEST(std::abs(w(Vec<3>(0.0, r / std::sqrt(2.0), r / std::sqrt(2.0)))) < 0.02);
}

// Sampled volume N dx³ against the analytic sphere volume 4/3 π R³: within 1 % at R = 20 dx
// (the inscribed polyhedron of 8192 faces is 0.1 % smaller; lattice counting adds < 0.5 %).
BOOST_AUTO_TEST_CASE(sampled_sphere_volume_matches_analytic) {
  const double R = 0.5, dx = R / 20.0;
  const auto points = sample_inside(sphere(R, 5), dx);
  const double sampled = points.size() * dx * dx * dx, exact = 4.0 / 3.0 * pi * R * R * R;
  BOOST_TEST(sampled == exact, boost::test_tools::tolerance(0.01));
  for (const Vec<3>& p : points) BOOST_TEST_REQUIRE(p.norm() < R);
}

BOOST_AUTO_TEST_CASE(loads_obj_and_reports_closed_topology) {
  const TriangleMesh m = load_obj(write_obj("cube", obj_text(unit_cube())));
  BOOST_TEST(m.vertices.size() == 8u);
  BOOST_TEST(m.triangles.size() == 12u);
  const EdgeReport r = edge_report(m);
  BOOST_TEST(r.edges == 18u);
  BOOST_TEST(r.boundary == 0u);
  BOOST_TEST(r.non_manifold == 0u);
  BOOST_TEST(!throws_input_error([&] { require_closed(m, "cube.obj"); }));
}

BOOST_AUTO_TEST_CASE(mesh_with_a_hole_is_refused) {
  TriangleMesh m = unit_cube();
  m.triangles.pop_back();
  BOOST_TEST(edge_report(m).boundary == 3u);
  BOOST_TEST(throws_input_error([&] { require_closed(m, "holed.obj"); }));
}

BOOST_AUTO_TEST_CASE(missing_empty_and_nan_meshes_are_input_errors) {
  BOOST_TEST(throws_input_error([] { load_obj("/nonexistent/mesh.obj"); }));
  BOOST_TEST(throws_input_error([] { load_obj(write_obj("empty", "# nothing\n")); }));
  BOOST_TEST(throws_input_error([] { load_obj(write_obj("points", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")); }));
  BOOST_TEST(throws_input_error([] { load_obj(write_obj("nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")); }));
  BOOST_TEST(throws_input_error([] { load_obj(write_obj("badindex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")); }));
}

BOOST_AUTO_TEST_CASE(placement_rotates_y_up_scales_to_size_and_moves_min_corner) {
  MeshPlacement p;
  p.up_axis = "y";
  p.size = 2.0;
  p.min_corner = {1.0, 2.0, 3.0};
  TriangleMesh box = unit_cube();
  for (Vec<3>& v : box.vertices) v.y() *= 0.5;  // 1 x 0.5 x 1, y up
  const TriangleMesh placed = place_mesh(box, p);
  BOOST_TEST((placed.bbox_min() - Vec<3>(1.0, 2.0, 3.0)).norm() < 1e-12);
  BOOST_TEST((placed.bbox_max() - Vec<3>(3.0, 4.0, 4.0)).norm() < 1e-12);  // the file's y is now z
  BOOST_TEST(placed.signed_volume() == 4.0, boost::test_tools::tolerance(1e-12));  // orientation kept
}

BOOST_AUTO_TEST_CASE(placement_scales_then_translates_by_the_given_vector) {
  // Without min_corner, `translation` moves the scaled mesh by its three components, each along its
  // own axis: the unit cube at scale 2 moved by (1, 2, 3) spans (1, 2, 3) to (3, 4, 5).
  MeshPlacement p;
  p.scale = 2.0;
  p.translation = {1.0, 2.0, 3.0};
  const TriangleMesh placed = place_mesh(unit_cube(), p);
  BOOST_TEST((placed.bbox_min() - Vec<3>(1.0, 2.0, 3.0)).norm() < 1e-12);
  BOOST_TEST((placed.bbox_max() - Vec<3>(3.0, 4.0, 5.0)).norm() < 1e-12);
  BOOST_TEST(placed.signed_volume() == 8.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(sampling_fills_a_box_of_three_different_sides_once_per_lattice_cell) {
  // A 0.2 x 0.3 x 0.5 m box at dx = 0.05 m holds 4 x 6 x 10 lattice cells; sample_inside gives one
  // point at the centre of each, every point once, so the points fill the box to half a spacing of
  // each face. Unequal sides tell every axis's cell count from the others'.
  TriangleMesh box = unit_cube();
  for (Vec<3>& v : box.vertices) v = v.cwiseProduct(Vec<3>(0.2, 0.3, 0.5));
  const double dx = 0.05;
  const auto points = sample_inside(box, dx);
  BOOST_TEST(points.size() == 4u * 6u * 10u);
  std::map<std::array<long, 3>, int> seen;
  for (const Vec<3>& p : points) {
    std::array<long, 3> cell{};
    for (int d = 0; d < 3; ++d) {
      const double k = p[d] / dx - 0.5;  // the cell's index: a whole number for a cell centre
      BOOST_TEST_REQUIRE(std::abs(k - std::round(k)) < 1e-9);
      cell[d] = std::lround(k);
    }
    ++seen[cell];
  }
  BOOST_TEST(seen.size() == points.size());  // no point twice
  const std::array<long, 3> cells{4, 6, 10};
  for (const auto& [cell, n] : seen)
    for (int d = 0; d < 3; ++d) BOOST_TEST_REQUIRE((cell[d] >= 0 && cell[d] < cells[d]));
}

BOOST_AUTO_TEST_SUITE_END()

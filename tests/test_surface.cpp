// Surface reconstruction [Zhu-Bridson 2005: Surface Reconstruction] (solver/surface/): a lone
// particle gives a sphere of its radius, a flat slab a plane, a block its particles' volume; every
// mesh is closed and consistently oriented; the mesh does not depend on the number of threads.
#include <omp.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <utility>

#include "surface/implicit_surface.hpp"
#include "surface/surface_mesh.hpp"

using namespace sc;
using namespace sc::surface;

namespace {

/// An nx × ny × nz lattice of spacing s from `lo` (particle centres at lo + (i + 1/2) s), each
/// moved by up to ±jitter/2 of s per axis.
std::vector<Vec<3>> lattice(int nx, int ny, int nz, double s, const Vec<3>& lo, double jitter = 0.0) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Vec<3>> x;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        x.push_back(lo + s * Vec<3>(i + 0.5 + jitter * u(rng), j + 0.5 + jitter * u(rng), k + 0.5 + jitter * u(rng)));
  return x;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(surface)

// [Zhu-Bridson 2005: Surface Reconstruction]: φ = |x − x̄| − r̄ is the exact distance to a lone
// particle's sphere, and a point between two equal particles reads the mean position: φ at the
// midpoint is −r, whatever the kernel weights.
BOOST_AUTO_TEST_CASE(surface_average_is_the_distance_to_the_mean_sphere) {
  const Vec<3> p(0.1, -0.2, 0.3), at(0.13, -0.16, 0.3);
  SurfaceAverage<3> one(at, 0.2);
  one.add(p, 0.04);
  BOOST_TEST(std::abs(one.phi() - ((at - p).norm() - 0.04)) < 1e-15);
  SurfaceAverage<3> far(at, 0.01);
  far.add(p, 0.04);
  BOOST_TEST(far.empty());
  const Vec<3> q = p + Vec<3>(0.02, 0.0, 0.0);
  SurfaceAverage<3> pair(0.5 * (p + q), 0.2);
  pair.add(p, 0.01);
  pair.add(q, 0.03);
  BOOST_TEST(std::abs(pair.phi() + 0.02) < 1e-15);
}

// The radius constant does what it says: on the plane half a spacing above a lattice's top layer
// (over one lattice cell, 6 × 6 points) φ is 0 within 0.2 % of the spacing on average.
BOOST_AUTO_TEST_CASE(lattice_radius_puts_a_flat_face_where_the_cubes_end) {
  const double s = 0.01;
  const std::vector<Vec<3>> x = lattice(13, 13, 9, s, Vec<3>(-6.5 * s, -6.5 * s, -8.5 * s));  // top layer at z = 0
  double mean = 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      SurfaceAverage<3> average(Vec<3>(0.1 * i * s, 0.1 * j * s, 0.5 * s), reach_factor * s);
      for (const auto& p : x) average.add(p, lattice_radius_factor * s);
      mean += average.phi() / 36.0;
    }
  BOOST_TEST_MESSAGE("flat lattice: mean phi " << mean / s << " s on the plane of the cubes' face");
  BOOST_TEST(std::abs(mean) < 0.002 * s);
}

// A lone particle reconstructs a sphere of its radius r: every mesh vertex within 1 % of r from its
// centre (a blobby sum of kernels would not: its radius depends on the kernel's falloff), and the
// enclosed volume within 3 % of 4/3 π r³.
BOOST_AUTO_TEST_CASE(one_particle_gives_a_sphere_of_its_radius) {
  const double s = 0.01;
  const SurfaceOptions options{s, 1.0 / 32.0, 1};
  const double r = options.radius();
  const std::vector<Vec<3>> x{Vec<3>(0.01234, -0.00711, 0.00423)};
  const SurfaceMesh mesh = reconstruct_surface(x, options);
  double worst = 0.0;
  for (const auto& p : mesh.points) worst = std::max(worst, std::abs((p - x[0]).norm() - r) / r);
  BOOST_TEST_MESSAGE("sphere: " << mesh.points.size() << " vertices, largest radius error " << worst);
  BOOST_TEST(mesh.points.size() > 100u);
  BOOST_TEST(worst < 0.01);
  BOOST_TEST(is_closed_and_oriented(mesh));
  const double exact = 4.0 / 3.0 * std::acos(-1.0) * r * r * r;
  BOOST_TEST(std::abs(enclosed_volume(mesh) / exact - 1.0) < 0.03);
}

// A flat slab (16 × 16 × 4 particles) gives a plane on top: the vertices over the slab's middle,
// two spacings from its edges, lie within 2 % of the spacing of their mean height.
BOOST_AUTO_TEST_CASE(flat_slab_gives_a_plane) {
  const double s = 0.01;
  const std::vector<Vec<3>> x = lattice(16, 16, 4, s, Vec<3>::Zero());
  const SurfaceMesh mesh = reconstruct_surface(x, {s, 0.25, 1});
  std::vector<double> top;
  for (const auto& p : mesh.points)
    if (p[2] > 3.0 * s && p[0] > 2.0 * s && p[0] < 14.0 * s && p[1] > 2.0 * s && p[1] < 14.0 * s) top.push_back(p[2]);
  double mean = 0.0;
  for (const double z : top) mean += z;
  mean /= static_cast<double>(top.size());
  double worst = 0.0;
  for (const double z : top) worst = std::max(worst, std::abs(z - mean));
  BOOST_TEST_MESSAGE("slab: " << top.size() << " top vertices at " << mean / s << " s, largest deviation " << worst / s << " s");
  BOOST_TEST(top.size() > 100u);
  BOOST_TEST(worst < 0.02 * s);
  BOOST_TEST(std::abs(mean - 4.0 * s) < 0.05 * s);  // at the particles' top face
  BOOST_TEST(is_closed_and_oriented(mesh));
}

// A block of 20³ jittered particles encloses their volume N s³ within 3 %.
BOOST_AUTO_TEST_CASE(block_encloses_its_particles_volume) {
  const double s = 0.01;
  const std::vector<Vec<3>> x = lattice(20, 20, 20, s, Vec<3>(-0.05, 0.02, 0.0), 0.3);
  const SurfaceMesh mesh = reconstruct_surface(x, {s, 0.25, 1});
  const double particles = static_cast<double>(x.size()) * s * s * s;
  BOOST_TEST_MESSAGE("block: volume " << enclosed_volume(mesh) / particles << " of N s^3");
  BOOST_TEST(std::abs(enclosed_volume(mesh) / particles - 1.0) < 0.03);
  BOOST_TEST(is_closed_and_oriented(mesh));
}

// Two separate blocks give two closed surfaces in one mesh, and the same mesh, bitwise, with 1 and
// 2 OpenMP threads and when built twice.
BOOST_AUTO_TEST_CASE(mesh_is_closed_and_thread_independent) {
  const double s = 0.01;
  std::vector<Vec<3>> x = lattice(6, 5, 4, s, Vec<3>::Zero(), 0.5);
  for (const auto& p : lattice(4, 4, 7, s, Vec<3>(0.12, 0.0, 0.0), 0.5)) x.push_back(p);
  const int saved = omp_get_max_threads();
  SurfaceMesh mesh[3];
  for (int run = 0; run < 3; ++run) {
    omp_set_num_threads(run == 0 ? 1 : 2);
    mesh[run] = reconstruct_surface(x, {s, 0.25, 1});
  }
  omp_set_num_threads(saved);
  BOOST_TEST(is_closed_and_oriented(mesh[0]));
  BOOST_TEST(enclosed_volume(mesh[0]) > 0.0);
  for (int run = 1; run < 3; ++run) {
    BOOST_TEST(mesh[run].points == mesh[0].points);
    BOOST_TEST(mesh[run].triangles == mesh[0].triangles);
  }
}

// The check the tests above lean on can fail: a tetrahedron with outward normals is closed and
// oriented (volume 1/6); without one face, three edges have one triangle each; with one face turned,
// its edges run the same way as its neighbours'; no triangles is no surface.
BOOST_AUTO_TEST_CASE(closedness_check_refuses_a_hole_and_a_turned_face) {
  SurfaceMesh tet;
  tet.points = {Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.0, 0.0, 0.0), Vec<3>(0.0, 1.0, 0.0), Vec<3>(0.0, 0.0, 1.0)};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  BOOST_TEST(is_closed_and_oriented(tet));
  BOOST_TEST(enclosed_volume(tet) == 1.0 / 6.0, boost::test_tools::tolerance(1e-15));
  SurfaceMesh holed = tet;
  holed.triangles.pop_back();
  BOOST_TEST(!is_closed_and_oriented(holed));
  SurfaceMesh turned = tet;
  std::swap(turned.triangles[3][1], turned.triangles[3][2]);
  BOOST_TEST(!is_closed_and_oriented(turned));
  BOOST_TEST(!is_closed_and_oriented(SurfaceMesh{}));
}

// Wet sand shown darker: a block of uniform saturation 0.3 gives 0.3 at every vertex (to round-off);
// a block whose left half is dry and right half saturated reads 0 at its left end and 1 at its
// right end, and the VTP carries the array.
BOOST_AUTO_TEST_CASE(vertices_carry_the_particles_saturation) {
  const double s = 0.01;
  const std::vector<Vec<3>> x = lattice(12, 6, 6, s, Vec<3>::Zero(), 0.3);
  SurfaceMesh mesh = reconstruct_surface(x, {s, 0.25, 1});
  attach_saturation(mesh, x, std::vector<double>(x.size(), 0.3), {s, 0.25, 1});
  double worst = 0.0;
  for (const double v : mesh.saturation) worst = std::max(worst, std::abs(v - 0.3));
  BOOST_TEST(mesh.saturation.size() == mesh.points.size());
  BOOST_TEST(worst < 1e-14);
  std::vector<double> halves;
  for (const auto& p : x) halves.push_back(p[0] < 6.0 * s ? 0.0 : 1.0);
  attach_saturation(mesh, x, halves, {s, 0.25, 1});
  double left = 0.0, right = 1.0;  // the wettest vertex of the left end, the driest of the right end
  int ends = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (mesh.points[v][0] < 2.0 * s) {
      left = std::max(left, mesh.saturation[v]);
      ++ends;
    }
    if (mesh.points[v][0] > 10.0 * s) {
      right = std::min(right, mesh.saturation[v]);
      ++ends;
    }
  }
  BOOST_TEST(ends > 100);
  BOOST_TEST(left == 0.0);
  BOOST_TEST(right == 1.0);
  BOOST_TEST(vtp_document(mesh).find("Name=\"saturation\"") != std::string::npos);
  std::vector<double> ramp;  // a saturation varying along x: each vertex the kernel mean over all particles
  for (const auto& p : x) ramp.push_back(p[0] / (12.0 * s));
  attach_saturation(mesh, x, ramp, {s, 0.25, 1});
  double off = 0.0;
  for (std::size_t v = 0; v < mesh.points.size(); v += 37) {
    double w_sum = 0.0, s_sum = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double q = (x[i] - mesh.points[v]).squaredNorm() / (4.0 * s * s);
      if (q >= 1.0) continue;
      w_sum += (1 - q) * (1 - q) * (1 - q);
      s_sum += (1 - q) * (1 - q) * (1 - q) * ramp[i];
    }
    off = std::max(off, std::abs(mesh.saturation[v] - s_sum / w_sum));
  }
  BOOST_TEST(off < 1e-12);
}

// The VTP document lists every point and triangle (ParaView's PolyData: connectivity and offsets).
BOOST_AUTO_TEST_CASE(vtp_document_lists_points_and_triangles) {
  const SurfaceMesh mesh = reconstruct_surface(lattice(3, 3, 3, 0.01, Vec<3>::Zero()), {0.01, 0.25, 1});
  const std::string doc = vtp_document(mesh);
  std::ostringstream head, last_offset, last_triangle;
  head << "NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfPolys=\"" << mesh.triangles.size() << "\"";
  last_offset << 3 * mesh.triangles.size() << "\n</DataArray>\n</Polys>";
  const auto& t = mesh.triangles.back();
  last_triangle << "\n" << t[0] << " " << t[1] << " " << t[2] << "\n</DataArray>";
  BOOST_TEST(mesh.triangles.size() > 10u);
  BOOST_TEST(doc.find(head.str()) != std::string::npos);
  BOOST_TEST(doc.find(last_offset.str()) != std::string::npos);
  BOOST_TEST(doc.find(last_triangle.str()) != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()

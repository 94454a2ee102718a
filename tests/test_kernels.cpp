// Kernels of Müller 2003 (docs/equations.md §1): normalisation, compact support, derivatives,
// antisymmetry of the gradient, positivity of the viscosity Laplacian.
#include <boost/test/unit_test.hpp>
#include <gsl/gsl_integration.h>

#include "sph/kernels.hpp"

using namespace sc;

namespace {

/// ∫ W dV by radial quadrature (GSL QAGS): 4π∫r²W dr in 3-D, 2π∫rW dr in 2-D.
template <int D, class F>
double radial_integral(F&& w, double h) {
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(1000);
  auto fn = [&](double r) { return (D == 3 ? 4.0 * pi * r * r : 2.0 * pi * r) * w(r); };
  gsl_function g;
  g.function = [](double r, void* p) { return (*static_cast<decltype(fn)*>(p))(r); };
  g.params = &fn;
  double result = 0.0, error = 0.0;
  gsl_integration_qags(&g, 1e-12, h, 0.0, 1e-13, 1000, ws, &result, &error);
  gsl_integration_workspace_free(ws);
  return result;
}

template <int D>
void check_normalisation(double h) {
  BOOST_TEST(radial_integral<D>([h](double r) { return kernel::poly6<D>(r, h); }, h) == 1.0, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(radial_integral<D>([h](double r) { return kernel::spiky<D>(r, h); }, h) == 1.0, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(radial_integral<D>([h](double r) { return kernel::viscosity<D>(r, h); }, h) == 1.0, boost::test_tools::tolerance(1e-8));
}

/// ∇W by central differences of W along a random direction, compared with the analytic gradient.
template <int D>
void check_gradients(double h) {
  Vec<D> dir = Vec<D>::Ones().normalized();
  for (double r : {0.1 * h, 0.37 * h, 0.8 * h}) {
    const Vec<D> d = r * dir;
    double eps = 1e-6 * h;
    const double dW6 = (kernel::poly6<D>(r + eps, h) - kernel::poly6<D>(r - eps, h)) / (2 * eps);
    const double dWs = (kernel::spiky<D>(r + eps, h) - kernel::spiky<D>(r - eps, h)) / (2 * eps);
    BOOST_TEST((kernel::poly6_gradient<D>(d, r, h) - dW6 * dir).norm() <= 1e-6 * std::abs(dW6));
    BOOST_TEST((kernel::spiky_gradient<D>(d, r, h) - dWs * dir).norm() <= 1e-6 * std::abs(dWs));
    // Laplacians: W'' + (D − 1) W'/r (larger step: second differences lose digits to round-off).
    eps = 1e-4 * h;
    auto lap = [&](auto w) {
      const double w1 = (w(r + eps) - w(r - eps)) / (2 * eps);
      const double w2 = (w(r + eps) - 2 * w(r) + w(r - eps)) / (eps * eps);
      return w2 + (D - 1) * w1 / r;
    };
    const double l6 = lap([h](double s) { return kernel::poly6<D>(s, h); });
    const double lv = lap([h](double s) { return kernel::viscosity<D>(s, h); });
    BOOST_TEST(kernel::poly6_laplacian<D>(r, h) == l6, boost::test_tools::tolerance(1e-4));
    BOOST_TEST(kernel::viscosity_laplacian<D>(r, h) == lv, boost::test_tools::tolerance(1e-4));
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(kernels)

BOOST_AUTO_TEST_CASE(normalisation_2d_and_3d) {
  check_normalisation<2>(0.1);
  check_normalisation<3>(0.1);
  check_normalisation<3>(2.5);
}

BOOST_AUTO_TEST_CASE(compact_support_and_positivity) {
  const double h = 0.3;
  BOOST_TEST(kernel::poly6<3>(h, h) == 0.0);
  BOOST_TEST(kernel::spiky<2>(h, h) == 0.0);
  BOOST_TEST(kernel::spiky_derivative<3>(h, h) == 0.0);
  BOOST_TEST(kernel::viscosity_laplacian<2>(h, h) == 0.0);
  for (double r = 0.0; r <= h; r += h / 50) {
    BOOST_TEST(kernel::poly6<2>(r, h) >= 0.0);
    BOOST_TEST(kernel::spiky<3>(r, h) >= 0.0);
    BOOST_TEST(kernel::viscosity_laplacian<3>(r, h) >= 0.0);
    BOOST_TEST(kernel::viscosity_laplacian<2>(r, h) >= 0.0);
  }
}

BOOST_AUTO_TEST_CASE(gradients_match_finite_differences) {
  check_gradients<2>(0.2);
  check_gradients<3>(0.2);
}

BOOST_AUTO_TEST_CASE(gradient_is_antisymmetric_and_points_towards_neighbour) {
  const Vec<3> xi(0.1, 0.2, 0.3), xj(0.15, 0.18, 0.33);
  const double r = (xi - xj).norm(), h = 0.1;
  const Vec<3> gij = kernel::spiky_gradient<3>(Vec<3>(xi - xj), r, h);
  const Vec<3> gji = kernel::spiky_gradient<3>(Vec<3>(xj - xi), r, h);
  BOOST_TEST((gij + gji).norm() == 0.0);
  BOOST_TEST(gij.dot(xj - xi) > 0.0);  // gradW_ij points from i towards j (docs/equations.md §0)
}

BOOST_AUTO_TEST_CASE(pair_average_of_equal_supports_has_the_bits_of_the_full_average) {
  // The one-evaluation path for h_i = h_j must give exactly (k(h_i) + k(h_j))/2, and the average is
  // symmetric in i and j for unequal supports. The kernels at a Support (constants looked up once)
  // have the bits of the kernels at h.
  const Vec<3> d(0.013, -0.021, 0.007);
  const double r = d.norm();
  auto grad = [&](const kernel::Support<3>& s) { return kernel::spiky_gradient<3>(d, r, s); };
  for (const double h : {0.03, 0.0417, 0.06}) {
    const kernel::Support<3> s(h);
    const Vec<3> full = 0.5 * (kernel::spiky_gradient<3>(d, r, h) + kernel::spiky_gradient<3>(d, r, h));
    const Vec<3> avg = kernel::pair_average(grad, s, h);
    BOOST_TEST((avg.array() == full.array()).all());
    const double lap = kernel::pair_average([r](const kernel::Support<3>& t) { return kernel::viscosity_laplacian<3>(r, t); }, s, h);
    BOOST_TEST(lap == 0.5 * (kernel::viscosity_laplacian<3>(r, h) + kernel::viscosity_laplacian<3>(r, h)));
    BOOST_TEST(kernel::poly6<3>(r, s) == kernel::poly6<3>(r, h));
    BOOST_TEST(kernel::spiky<3>(r, s) == kernel::spiky<3>(r, h));
  }
  const kernel::Support<3> a(0.03), b(0.05);
  const Vec<3> ij = kernel::pair_average(grad, a, 0.05), ji = kernel::pair_average(grad, b, 0.03);
  BOOST_TEST((ij.array() == ji.array()).all());
  BOOST_TEST((ij - 0.5 * (grad(a) + grad(b))).norm() == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()

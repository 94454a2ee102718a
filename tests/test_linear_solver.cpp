// core/conjugate_gradient.hpp: the dot product in one order for every instruction set, and the
// conjugate gradients built on it (the solver of porous/rigid_pore_pressure.cpp).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/conjugate_gradient.hpp"
#include "support/pattern.hpp"

using namespace sc;

namespace {

Eigen::VectorXd values(const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())); }

/// The 1-D Laplacian tridiag(−1, 2, −1) of n unknowns between u = 0 on the left and u = 1 on the
/// right, as (A, b); its solution is u_k = (k + 1)/(n + 1).
std::pair<Eigen::SparseMatrix<double>, Eigen::VectorXd> poisson_1d(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < n; ++k) {
    entries.emplace_back(k, k, 2.0);
    if (k > 0) entries.emplace_back(k, k - 1, -1.0);
    if (k + 1 < n) entries.emplace_back(k, k + 1, -1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b[n - 1] = 1.0;
  return {A, b};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(linear_solver)

BOOST_AUTO_TEST_CASE(ordered_dot_adds_in_its_one_order) {
  // Terms whose sum depends on the order (1 + 2^-53 rounds to 1, ties to even), the second
  // factor 1 or 2 (exact products):
  const double e = std::ldexp(1.0, -53), big = std::ldexp(1.0, 53);
  const auto ones = [](int n) { return Eigen::VectorXd::Ones(n); };
  // Six terms: the two small ones meet in the partial sum of the odd terms before they meet 1,
  // so the sum is 1 + 2^-52; left to right, or in the order of Eigen's AVX2 dot product (four
  // lanes, then the last two terms one at a time), each is lost against 1 and the sum is 1.
  BOOST_TEST(ordered_dot(values({1.0, 0.0, 0.0, e, 0.0, e}), ones(6)) == 1.0 + 2.0 * e);
  BOOST_TEST(ordered_dot(values({0.5, 0.0, 0.0, e, 0.0, e}), values({2.0, 1.0, 1.0, 1.0, 1.0, 1.0})) == 1.0 + 2.0 * e);
  // Sixteen terms: terms 0, 4, 8, 12 share a partial sum, added in that order, ((2^53 + 1) − 2^53) + 1
  // = 1; Eigen's AVX2 dot product pairs them as (2^53 − 2^53) + (1 + 1) = 2.
  std::vector<double> sixteen(16, 0.0);
  sixteen[0] = big;
  sixteen[4] = 1.0;
  sixteen[8] = -big;
  sixteen[12] = 1.0;
  BOOST_TEST(ordered_dot(values(sixteen), ones(16)) == 1.0);
  // Fewer than four terms: left to right, (1 + 2^-53) + 2^-53 = 1.
  BOOST_TEST(ordered_dot(values({1.0, e, e}), ones(3)) == 1.0);
  BOOST_TEST(ordered_dot(values({}), ones(0)) == 0.0);
  BOOST_TEST(ordered_dot(values({-3.0}), values({2.0})) == -6.0);
}

BOOST_AUTO_TEST_CASE(ordered_dot_takes_every_term_at_every_length) {
  // Small whole numbers add exactly in any order, so for every length the dot product is the exact
  // sum: a term dropped or taken twice (at the end of the blocks of four, the pair after them or
  // the odd last one) changes it.
  for (int n = 0; n <= 21; ++n) {
    Eigen::VectorXd a(n), b(n);
    double exact = 0.0;
    for (int k = 0; k < n; ++k) {
      a[k] = k + 1.0;
      b[k] = (k % 3) - 1.5;
      exact += a[k] * b[k];
    }
    BOOST_TEST(ordered_dot(a, b) == exact, "length " << n);
  }
}

BOOST_AUTO_TEST_CASE(conjugate_gradient_solves_the_discrete_poisson_equation) {
  // A linear profile between two Dirichlet values, from a zero guess: every unknown within 1e-8
  // (tolerance 1e-10 on the relative residual, condition number about 4 (n + 1)²/π² ≈ 1e3), in at
  // most n iterations. Started at the solution it takes none and leaves it as it is; b = 0 gives 0.
  const int n = 50;
  const auto [A, b] = poisson_1d(n);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const Eigen::Index iterations = conjugate_gradient(A, b, x, 1e-10);
  BOOST_TEST(iterations > 0);
  BOOST_TEST(iterations <= n);
  Eigen::VectorXd exact(n);
  for (int k = 0; k < n; ++k) exact[k] = (k + 1.0) / (n + 1.0);
  BOOST_TEST((x - exact).cwiseAbs().maxCoeff() <= 1e-8);
  Eigen::VectorXd warm = exact;
  BOOST_TEST(conjugate_gradient(A, b, warm, 1e-10) == 0);
  BOOST_TEST((warm.array() == exact.array()).all());
  Eigen::VectorXd zero_rhs = exact;
  conjugate_gradient(A, Eigen::VectorXd::Zero(n), zero_rhs, 1e-10);
  BOOST_TEST((zero_rhs.array() == 0.0).all());
}

BOOST_AUTO_TEST_CASE(no_solver_source_uses_eigens_iterative_solvers) {
  // Eigen's iterative solvers take their dot products with Eigen's SIMD reductions, whose order
  // follows the packet width, so an SSE and an AVX2 build would solve to other bits. A build for
  // one instruction set cannot see that in its results; the sources can: the solver's systems go
  // through conjugate_gradient.
  const test::Pattern eigen_solver(R"(#include\s*<Eigen/(IterativeLinearSolvers|Sparse|Eigen)>|ConjugateGradient<|BiCGSTAB<)"),
      comment(R"(^\s*//)");
  const std::filesystem::path solver = std::filesystem::path(SANDCASTLE_SOURCE_DIR) / "solver";
  int files = 0;
  std::string found;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(solver)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    std::ifstream in(entry.path());
    int line_number = 0;
    for (std::string line; std::getline(in, line);) {
      ++line_number;
      if (!comment.found_in(line) && eigen_solver.found_in(line))
        found += entry.path().string() + ":" + std::to_string(line_number) + ": " + line + "\n";
    }
  }
  BOOST_TEST(files > 50);
  BOOST_TEST(found.empty(), found);
}

BOOST_AUTO_TEST_SUITE_END()

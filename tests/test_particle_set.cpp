// ParticleSet: queued removal and addition in a stable order, checksums.
#include <boost/test/unit_test.hpp>

#include "core/particle_set.hpp"

using namespace sc;

BOOST_AUTO_TEST_SUITE(particle_set)

BOOST_AUTO_TEST_CASE(compact_removes_in_index_order_then_appends_in_queue_order) {
  ParticleSet<2> ps;
  for (int k = 0; k < 6; ++k) ps.x[ps.append()] = Vec<2>(k, 0);
  ps.queue_remove(4);
  ps.queue_remove(1);
  ps.additions().x[ps.additions().append()] = Vec<2>(10, 0);
  ps.additions().x[ps.additions().append()] = Vec<2>(11, 0);
  BOOST_TEST(ps.compact());
  const std::vector<double> expected{0, 2, 3, 5, 10, 11};
  BOOST_TEST_REQUIRE(ps.size() == expected.size());
  for (std::size_t i = 0; i < ps.size(); ++i) BOOST_TEST(ps.x[i][0] == expected[i]);
  BOOST_TEST(ps.id[4] == 6);  // new particles get fresh ids, never reused
  BOOST_TEST(ps.id[5] == 7);
  BOOST_TEST(ps.m.size() == ps.size());
  BOOST_TEST(!ps.compact());
}

BOOST_AUTO_TEST_CASE(checksum_sees_every_bit_of_position_and_velocity) {
  ParticleSet<3> ps;
  ps.append();
  const std::string a = ps.checksum();
  ps.v[0][2] = 1e-300;
  BOOST_TEST(ps.checksum() != a);
}

BOOST_AUTO_TEST_SUITE_END()

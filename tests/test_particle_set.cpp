// ParticleSet: queued removal and addition in a stable order, checksums, layouts.
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

BOOST_AUTO_TEST_CASE(copy_from_equals_assignment) {
  ParticleSet<3> a, b, c;
  for (int k = 0; k < 1000; ++k) {
    const std::size_t i = a.append();
    a.x[i] = Vec<3>(k, 0.5 * k, -k);
    a.v[i] = Vec<3>(1.0 / (k + 1), 0, 2);
    a.m[i] = 1e-3 * k;
  }
  a.queue_remove(3);
  a.additions().append();
  for (int k = 0; k < 5; ++k) b.append();  // other sizes are replaced
  b.copy_from(a);
  c = a;
  BOOST_TEST(b.checksum() == c.checksum());
  BOOST_TEST(b.m == c.m);
  BOOST_TEST(b.id == c.id);
  BOOST_TEST(b.next_id() == c.next_id());
  BOOST_TEST(b.compact() == c.compact());  // the queued removal and addition were copied
  BOOST_TEST(b.size() == c.size());
  BOOST_TEST(b.checksum() == c.checksum());
}

// A halo appended and truncated again gives the set back its layout (the blow-up guard of a
// decomposed run then refreshes its copy); a reorder does not, and no layout value comes back for
// another order of particles.
BOOST_AUTO_TEST_CASE(truncating_what_was_appended_restores_the_layout) {
  ParticleSet<2> ps;
  for (int k = 0; k < 4; ++k) ps.x[ps.append()] = Vec<2>(k, 0);
  const std::uint64_t own = ps.layout();
  for (int k = 0; k < 2; ++k) ps.additions().append();
  ps.compact();
  const std::uint64_t with_halo = ps.layout();
  BOOST_TEST(with_halo != own);
  ps.truncate(4);
  BOOST_TEST(ps.layout() == own);
  ps.additions().append();
  ps.compact();
  BOOST_TEST(ps.layout() != with_halo);  // another halo, another layout
  ps.truncate(3);  // not where the appends began
  BOOST_TEST(ps.layout() != own);
  const std::uint64_t three = ps.layout();
  ps.additions().append();
  ps.compact();
  ps.permute({0, 2, 1, 3});
  ps.truncate(3);  // reordered since: a new layout
  BOOST_TEST(ps.layout() != three);
}

BOOST_AUTO_TEST_CASE(permute_puts_every_field_of_every_particle_where_the_order_says) {
  // Orders of the kinds a run makes: a shuffle, a removal (compact), the migration reorder of a
  // decomposed run (particles gone and arrivals merged in front of a block of walls that only
  // shifts), and the whole set shifted as one block. Each field is compared with the definition
  // new[k] = old[order[k]], for a vector field, a number and a byte field.
  const std::size_t n = 40;
  std::vector<std::vector<std::size_t>> orders;
  std::vector<std::size_t> shuffle(n);
  for (std::size_t k = 0; k < n; ++k) shuffle[k] = (7 * k + 3) % n;
  orders.push_back(shuffle);
  std::vector<std::size_t> removal;
  for (std::size_t k = 0; k < n; ++k)
    if (k % 5 != 2) removal.push_back(k);
  orders.push_back(removal);
  std::vector<std::size_t> migration = {0, 38, 1, 3, 4, 39, 6};  // 2 and 5 left, 38 and 39 arrived
  for (std::size_t k = 8; k < 38; ++k) migration.push_back(k);     // then the walls, one block
  orders.push_back(migration);
  std::vector<std::size_t> block;
  for (std::size_t k = 3; k < n; ++k) block.push_back(k);
  orders.push_back(block);
  orders.push_back({n - 1});
  for (const auto& order : orders) {
    ParticleSet<3> ps;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = ps.append();
      ps.x[i] = Vec<3>(k, 2.0 * k, -1.0 * k);
      ps.m[i] = 0.5 + k;
      ps.rough[i] = static_cast<std::uint8_t>(k);
    }
    const std::vector<std::int64_t> ids(ps.id.begin(), ps.id.end());
    ps.permute(order);
    BOOST_TEST_REQUIRE(ps.size() == order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto o = static_cast<double>(order[k]);
      BOOST_TEST((ps.x[k] == Vec<3>(o, 2.0 * o, -o)));
      BOOST_TEST(ps.m[k] == 0.5 + o);
      BOOST_TEST(ps.rough[k] == order[k]);
      BOOST_TEST(ps.id[k] == ids[order[k]]);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

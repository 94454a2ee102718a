// The checkpoint format (solver/io/checkpoint.hpp): every particle field and the run state survive
// a round trip bit for bit; truncation, corruption, another format version or dimension is an
// InputError naming the file.
#include <boost/test/unit_test.hpp>
#include <cstring>

#include "io/checkpoint.hpp"

using namespace sc;

namespace {

/// Particles whose every field (whatever fields ParticleSet has) holds a distinct byte pattern; with
/// or without the porous-flow fields.
ParticleSet<2> patterned_particles(std::size_t n, bool porous = true) {
  ParticleSet<2> ps;
  if (porous) ps.add_porous_fields();
  for (std::size_t i = 0; i < n; ++i) ps.append();
  unsigned char next = 1;
  ps.visit_fields([&](std::string_view, auto& field) {
    auto* bytes = reinterpret_cast<unsigned char*>(static_cast<void*>(field.data()));
    for (std::size_t k = 0; k < field.size() * sizeof(field[0]); ++k) bytes[k] = next += 37;
  });
  return ps;
}

CheckpointState sample_state() {
  CheckpointState s;
  s.spacing = 0.01;
  s.parameters_hash = "0123456789abcdef";
  s.time = 0.1 + 0.2;  // not exactly 0.3: must come back bit for bit
  s.step = 4242;
  s.last_dt = 1.0 / 3.0 * 1e-3;
  s.run = {{"frames", json::array({json::array({0.0, "frame_00000.vtu"})})}, {"next_frame", 0.05}};
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(checkpoint)

BOOST_AUTO_TEST_CASE(round_trip_keeps_every_field_and_the_state_bitwise) {
  const CheckpointState state = sample_state();
  auto collect = [](std::vector<std::string>& out) {
    return [&out](std::string_view, const auto& field) {
      out.emplace_back(reinterpret_cast<const char*>(field.data()), field.size() * sizeof(field[0]));
    };
  };
  for (const bool porous : {true, false}) {  // a porous scene's set and one without those fields
    const ParticleSet<2> ps = patterned_particles(17, porous);
    const ParticleSet<2> back = restore_particles<2>(parse_checkpoint(checkpoint_document(ps, state), "mem.ckpt"));
    std::vector<std::string> written, restored;
    ps.visit_fields(collect(written));
    back.visit_fields(collect(restored));
    BOOST_TEST(back.has_porous_fields() == porous);
    BOOST_TEST(written == restored);
    BOOST_TEST(written.size() == (porous ? 23u : 16u));  // every field, or all but the seven porous ones
  }
  const ParticleSet<2> ps = patterned_particles(17);
  const Checkpoint c = parse_checkpoint(checkpoint_document(ps, state), "mem.ckpt");
  const ParticleSet<2> back = restore_particles<2>(c);
  BOOST_TEST(back.next_id() == ps.next_id());
  BOOST_TEST(std::memcmp(&c.state.time, &state.time, sizeof(double)) == 0);
  BOOST_TEST(std::memcmp(&c.state.last_dt, &state.last_dt, sizeof(double)) == 0);
  BOOST_TEST(c.state.step == 4242);
  BOOST_TEST(c.state.spacing == 0.01);
  BOOST_TEST(c.state.parameters_hash == "0123456789abcdef");
  BOOST_TEST(c.state.run == state.run);
}

BOOST_AUTO_TEST_CASE(truncation_and_corruption_are_rejected) {
  const std::string doc = checkpoint_document(patterned_particles(5), sample_state());
  for (std::size_t length : {std::size_t{0}, std::size_t{7}, std::size_t{30}, doc.size() / 2, doc.size() - 1})
    BOOST_CHECK_THROW(parse_checkpoint(doc.substr(0, length), "cut.ckpt"), InputError);
  for (std::size_t at = 0; at < doc.size(); at += 7) {
    std::string bad = doc;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    BOOST_CHECK_THROW(parse_checkpoint(bad, "flipped.ckpt"), InputError);
  }
}

BOOST_AUTO_TEST_CASE(other_version_and_dimension_are_named) {
  std::string doc = checkpoint_document(patterned_particles(3), sample_state());
  try {
    restore_particles<3>(parse_checkpoint(doc, "two_d.ckpt"));
    BOOST_FAIL("a 2-D checkpoint restored as 3-D");
  } catch (const InputError& e) {
    BOOST_TEST(e.file() == "two_d.ckpt");
    BOOST_TEST(e.json_path() == "/dimension");
  }
  doc[8] = 2;  // format version 2 (the checksum then fails too; the version is reported first)
  try {
    parse_checkpoint(doc, "v2.ckpt");
    BOOST_FAIL("version 2 accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.rule().find("format version 2") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(missing_file_is_an_input_error) {
  BOOST_CHECK_THROW(read_checkpoint("/nonexistent/run/checkpoint_00000010.ckpt"), InputError);
}

BOOST_AUTO_TEST_SUITE_END()

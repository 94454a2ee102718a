#include "io/checkpoint.hpp"

#include <algorithm>
#include <climits>
#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "io/atomic_file.hpp"

namespace sc {

namespace {

constexpr char kMagic[8] = {'S', 'A', 'N', 'D', 'C', 'K', 'P', 'T'};
constexpr std::size_t kPreamble = 8 + 4 + 8;  // magic, version, header length
constexpr std::size_t kTrailer = 8;           // checksum

std::uint64_t fnv1a(const char* data, std::size_t n) {
  std::uint64_t hash = 1469598103934665603ull;
  for (std::size_t k = 0; k < n; ++k) {
    hash ^= static_cast<unsigned char>(data[k]);
    hash *= 1099511628211ull;
  }
  return hash;
}

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <class T>
T get(const std::string& in, std::size_t offset) {
  T value;
  std::memcpy(&value, in.data() + offset, sizeof value);
  return value;
}

/// Per-particle layout of a field's element type: its scalar type and how many per particle.
template <class E>
struct FieldLayout {
  using Scalar = E;
  static constexpr std::size_t components = 1;
};
template <class S, int R, int C, int O, int MR, int MC>
struct FieldLayout<Eigen::Matrix<S, R, C, O, MR, MC>> {
  using Scalar = S;
  static constexpr std::size_t components = static_cast<std::size_t>(R * C);
};

template <class S>
constexpr const char* type_name() {
  if constexpr (std::is_same_v<S, double>) return "f64";
  else if constexpr (std::is_same_v<S, std::int64_t>) return "i64";
  else if constexpr (std::is_same_v<S, std::int32_t>) return "i32";
  else {
    static_assert(std::is_same_v<S, std::uint8_t>, "checkpoint: give this field type a name here");
    return "u8";
  }
}

std::size_t type_size(const std::string& type) {
  return type == "f64" || type == "i64" ? 8 : (type == "i32" ? 4 : 1);
}

/// Reads the header's fields and block table; blocks must tile [data_begin, data_end) exactly.
void read_header(JsonObject o, Checkpoint& c, std::size_t data_begin, std::size_t data_end) {
  CheckpointState& s = c.state;
  s.dimension = static_cast<int>(o.integer("dimension", 2, 3));
  s.spacing = o.positive("spacing");
  s.parameters_hash = o.string("parameters_hash");
  s.time = o.number("time");
  s.step = o.integer("step", 0, LONG_MAX);
  s.last_dt = o.number("last_dt");
  c.next_id = o.integer("next_id", 0, LONG_MAX);
  c.particles = static_cast<std::size_t>(o.integer("particles", 0, static_cast<long>(data_end)));
  s.run = o.raw("run");
  std::size_t offset = data_begin;
  for (JsonObject b : o.objects("blocks")) {
    CheckpointBlock block;
    block.name = b.string("name");
    block.type = b.one_of("type", {"f64", "i64", "i32", "u8"});
    block.components = static_cast<std::size_t>(b.integer("components", 1, 16));
    block.count = static_cast<std::size_t>(b.integer("count", 0, static_cast<long>(data_end)));
    block.bytes = static_cast<std::size_t>(b.integer("bytes", 0, static_cast<long>(data_end - offset)));
    if (block.bytes != block.count * block.components * type_size(block.type))
      b.fail("bytes", "must equal count x components x element size");
    block.offset = offset;
    offset += block.bytes;
    b.finish();
    c.blocks.push_back(block);
  }
  if (offset != data_end) o.fail("blocks", "block sizes do not add up to the data in the file");
  o.finish();
}

}  // namespace

template <int D>
std::string checkpoint_document(const ParticleSet<D>& ps, const CheckpointState& s) {
  json blocks = json::array();
  std::string data;
  ps.visit_fields([&](std::string_view name, const auto& field) {
    using E = typename std::decay_t<decltype(field)>::value_type;
    using L = FieldLayout<E>;
    static_assert(sizeof(E) == sizeof(typename L::Scalar) * L::components, "field elements must be packed");
    const std::size_t bytes = field.size() * sizeof(E);
    blocks.push_back({{"name", "particle/" + std::string(name)}, {"type", type_name<typename L::Scalar>()},
                      {"components", L::components}, {"count", field.size()}, {"bytes", bytes}});
    data.append(reinterpret_cast<const char*>(field.data()), bytes);
  });
  const json header = {{"dimension", D}, {"spacing", s.spacing}, {"parameters_hash", s.parameters_hash},
                       {"time", s.time}, {"step", s.step}, {"last_dt", s.last_dt}, {"next_id", ps.next_id()},
                       {"particles", ps.size()}, {"run", s.run}, {"blocks", blocks}};
  const std::string text = header.dump();
  std::string out(kMagic, sizeof kMagic);
  put<std::uint32_t>(out, kCheckpointVersion);
  put<std::uint64_t>(out, text.size());
  out += text;
  out += data;
  put<std::uint64_t>(out, fnv1a(out.data(), out.size()));
  return out;
}

template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps, const CheckpointState& state) {
  write_file_atomic(path, checkpoint_document(ps, state));
}

Checkpoint parse_checkpoint(std::string bytes, const std::string& file) {
  auto fail = [&file](const std::string& rule) { throw InputError(file, "", rule); };
  if (bytes.size() < kPreamble + kTrailer || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    fail("not a sandcastle checkpoint (no SANDCKPT magic, or too short)");
  const auto version = get<std::uint32_t>(bytes, 8);
  if (version != kCheckpointVersion)
    fail("checkpoint format version " + std::to_string(version) + "; this build reads version " +
         std::to_string(kCheckpointVersion));
  const std::size_t body = bytes.size() - kTrailer;
  if (get<std::uint64_t>(bytes, body) != fnv1a(bytes.data(), body))
    fail("checksum mismatch: the checkpoint is truncated or corrupt");
  const auto header_length = get<std::uint64_t>(bytes, 12);
  if (header_length > body - kPreamble) fail("header length exceeds the file");
  json header;
  try {
    header = json::parse(bytes.substr(kPreamble, header_length));
  } catch (const json::parse_error& e) {
    fail(std::string("header is not valid JSON: ") + e.what());
  }
  Checkpoint c;
  c.file = file;
  read_header(JsonObject(header, "", file), c, kPreamble + header_length, body);
  c.bytes = std::move(bytes);
  return c;
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "checkpoint cannot be opened (missing or unreadable)");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_checkpoint(buf.str(), path);
}

template <int D>
ParticleSet<D> restore_particles(const Checkpoint& c) {
  if (c.state.dimension != D)
    throw InputError(c.file, "/dimension", "checkpoint is " + std::to_string(c.state.dimension) +
                                               "-D but the case is " + std::to_string(D) + "-D");
  ParticleSet<D> ps;
  const auto holds = [&c](const std::string& block) {
    return std::ranges::any_of(c.blocks, [&](const CheckpointBlock& b) { return b.name == block; });
  };
  if (holds("particle/porosity")) ps.add_porous_fields();  // a porous scene's (see has_porous_fields)
  std::size_t used = 0;
  ps.visit_fields([&](std::string_view name, auto& field) {
    using E = typename std::decay_t<decltype(field)>::value_type;
    using L = FieldLayout<E>;
    const std::string block_name = "particle/" + std::string(name);
    for (std::size_t k = 0; k < c.blocks.size(); ++k) {
      const CheckpointBlock& b = c.blocks[k];
      if (b.name != block_name) continue;
      if (b.type != type_name<typename L::Scalar>() || b.components != L::components || b.count != c.particles)
        throw InputError(c.file, "/blocks/" + std::to_string(k),
                         block_name + " must hold " + std::to_string(c.particles) + " x " +
                             std::to_string(L::components) + " " + type_name<typename L::Scalar>());
      field.resize(b.count);
      std::memcpy(static_cast<void*>(field.data()), c.bytes.data() + b.offset, b.bytes);
      ++used;
      return;
    }
    throw InputError(c.file, "/blocks", "no block " + block_name + " (checkpoint from an older build?)");
  });
  if (used != c.blocks.size())
    throw InputError(c.file, "/blocks", "holds blocks this build does not know (checkpoint from a newer build?)");
  ps.set_next_id(c.next_id);
  return ps;
}

template std::string checkpoint_document<2>(const ParticleSet<2>&, const CheckpointState&);
template std::string checkpoint_document<3>(const ParticleSet<3>&, const CheckpointState&);
template void write_checkpoint<2>(const std::string&, const ParticleSet<2>&, const CheckpointState&);
template void write_checkpoint<3>(const std::string&, const ParticleSet<3>&, const CheckpointState&);
template ParticleSet<2> restore_particles<2>(const Checkpoint&);
template ParticleSet<3> restore_particles<3>(const Checkpoint&);

}  // namespace sc

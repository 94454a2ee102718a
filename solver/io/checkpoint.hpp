// Versioned binary checkpoints: every particle field (ParticleSet::visit_fields), the clock, the
// simulator's own carried state and what identifies the run (dimension, spacing, parameters hash),
// so a stopped run resumes bitwise identically (`sandcastle run --resume FILE`).
//
// Layout (little-endian, the only byte order the solver runs on):
//   8 bytes  magic "SANDCKPT"
//   u32      format version (kCheckpointVersion)
//   u64      header length n, then n bytes of header: JSON text
//              {"dimension", "spacing", "parameters_hash", "time", "step", "last_dt", "next_id",
//               "particles", "run": {...caller's bookkeeping...},
//               "blocks": [{"name", "type": "f64"|"i64"|"i32"|"u8", "components", "count", "bytes"}]}
//   ...      the blocks' bytes, in header order, each `count * components` elements
//   u64      FNV-1a 64 of every byte before it (detects truncation and corruption)
// Particle fields are blocks named "particle/<field>". A new field (or a new kind of state, e.g.
// "cluster/<field>") is one more block: readers find blocks by name, and a checkpoint that lacks
// a block the reader needs, or holds one of another type or size, is rejected with an InputError.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/particle_set.hpp"
#include "io/json_reader.hpp"

namespace sc {

inline constexpr std::uint32_t kCheckpointVersion = 1;

/// Everything in a checkpoint besides the particle fields.
struct CheckpointState {
  int dimension = 2;
  double spacing = 0.0;         ///< [m] particle spacing of the run
  std::string parameters_hash;  ///< of the case (CaseSpec::parameters_hash)
  double time = 0.0;            ///< [s]
  long step = 0;
  double last_dt = 0.0;         ///< [s] the previous step (the sand rigid stress needs it)
  json run = json::object();    ///< the runner's bookkeeping (frames written, next frame time)
};

/// One block of a checkpoint as listed in its header.
struct CheckpointBlock {
  std::string name, type;
  std::size_t components = 0, count = 0, offset = 0, bytes = 0;
};

/// A checkpoint read from disk and verified (magic, version, header, block sizes, checksum).
struct Checkpoint {
  std::string file;
  std::string bytes;  ///< the whole file
  CheckpointState state;
  std::size_t particles = 0;
  std::int64_t next_id = 0;  ///< ParticleSet::next_id() when written
  std::vector<CheckpointBlock> blocks;
};

/// The bytes of a checkpoint of `ps` with `state`.
template <int D>
std::string checkpoint_document(const ParticleSet<D>& ps, const CheckpointState& state);

/// Writes a checkpoint atomically (temporary file + rename).
template <int D>
void write_checkpoint(const std::string& path, const ParticleSet<D>& ps, const CheckpointState& state);

/// Parses and verifies checkpoint bytes; `file` names them in errors. Throws InputError.
Checkpoint parse_checkpoint(std::string bytes, const std::string& file);

/// Reads and verifies a checkpoint file. Throws InputError (missing, truncated, corrupt, other version).
Checkpoint read_checkpoint(const std::string& path);

/// The particles stored in `c`: every field of ParticleSet<D> from its block. Throws InputError
/// if the dimension differs or a field's block is missing or of another type or size.
template <int D>
ParticleSet<D> restore_particles(const Checkpoint& c);

}  // namespace sc

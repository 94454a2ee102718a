#include "parallel/decomposition.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "neighbours/neighbour_grid.hpp"

namespace sc {

namespace {

/// Particles `which` of ps with their keys, as bytes: their count, their keys, then each field's
/// values (ParticleSet::visit_fields order).
template <int D>
std::string pack(const ParticleSet<D>& ps, const std::vector<std::uint32_t>& which, const std::vector<std::uint64_t>& key) {
  std::string out;
  const std::uint64_t n = which.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  for (const std::uint32_t i : which) out.append(reinterpret_cast<const char*>(&key[i]), sizeof key[i]);
  ps.visit_fields([&](std::string_view, const auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    for (const std::uint32_t i : which) out.append(static_cast<const char*>(field_bytes(field[i])), sizeof(T));
  });
  return out;
}

/// Appends the particles of `bytes` (pack) to `into` and their keys to `keys`.
template <int D>
void unpack(const std::string& bytes, ParticleSet<D>& into, std::vector<std::uint64_t>& keys) {
  if (bytes.empty()) return;
  std::uint64_t n = 0;
  std::size_t at = 0;
  std::memcpy(&n, bytes.data(), sizeof n);
  at += sizeof n;
  const std::size_t old_keys = keys.size();
  keys.resize(old_keys + n);
  std::memcpy(keys.data() + old_keys, bytes.data() + at, n * sizeof(std::uint64_t));
  at += n * sizeof(std::uint64_t);
  into.visit_fields([&](std::string_view, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    const std::size_t old = field.size();
    field.resize(old + n);
    for (std::size_t k = 0; k < n; ++k, at += sizeof(T)) std::memcpy(field_bytes(field[old + k]), bytes.data() + at, sizeof(T));
  });
}

std::vector<std::uint32_t> all_indices(std::size_t n) {
  std::vector<std::uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  return all;
}

/// The order that puts `key` in ascending order (identity when it already is).
std::vector<std::size_t> key_order(const std::vector<std::uint64_t>& key) {
  std::vector<std::size_t> order(key.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (!std::is_sorted(key.begin(), key.end()))
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}

constexpr std::int64_t kNoBorder = std::numeric_limits<std::int64_t>::max();

template <class T>
void put(std::string& out, const T& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
template <class T>
T take(const std::string& in, std::size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

/// A CompactionNotice as bytes: the count, the removed keys, the additions' orders.
std::string encode(const CompactionNotice& n) {
  std::string out;
  put(out, n.particles);
  put(out, static_cast<std::uint64_t>(n.removed.size()));
  for (const std::uint64_t k : n.removed) put(out, k);
  put(out, static_cast<std::uint64_t>(n.added.size()));
  for (const AdditionOrder& a : n.added) {
    put(out, a.queuer);
    put(out, a.place);
  }
  return out;
}

CompactionNotice decode(const std::string& in) {
  CompactionNotice n;
  std::size_t at = 0;
  n.particles = take<std::uint64_t>(in, at);
  n.removed.resize(take<std::uint64_t>(in, at));
  for (std::uint64_t& k : n.removed) k = take<std::uint64_t>(in, at);
  n.added.resize(take<std::uint64_t>(in, at));
  for (AdditionOrder& a : n.added) {
    a.queuer = take<std::uint64_t>(in, at);
    a.place = take<std::uint64_t>(in, at);
  }
  return n;
}

}  // namespace

CompactionKeys compaction_keys(const std::vector<std::uint64_t>& kept, const std::vector<AdditionOrder>& mine,
                               const std::vector<CompactionNotice>& every_rank) {
  std::uint64_t total = 0;
  std::vector<std::uint64_t> removed;
  std::vector<AdditionOrder> added;
  for (const CompactionNotice& n : every_rank) {
    total += n.particles;
    removed.insert(removed.end(), n.removed.begin(), n.removed.end());
    added.insert(added.end(), n.added.begin(), n.added.end());
  }
  std::sort(removed.begin(), removed.end());
  std::sort(added.begin(), added.end());
  CompactionKeys out;
  out.survivors = total - removed.size();
  out.additions = added.size();
  out.kept.reserve(kept.size());
  for (const std::uint64_t k : kept)
    out.kept.push_back(k - static_cast<std::uint64_t>(std::lower_bound(removed.begin(), removed.end(), k) - removed.begin()));
  out.added.reserve(mine.size());
  for (const AdditionOrder& a : mine)
    out.added.push_back(out.survivors + static_cast<std::uint64_t>(std::lower_bound(added.begin(), added.end(), a) - added.begin()));
  return out;
}

template <int D>
int Decomposition<D>::owner(std::int64_t c) const {
  return static_cast<int>(std::upper_bound(cut_.begin(), cut_.end(), c) - cut_.begin());
}

template <int D>
void Decomposition<D>::find_grid(const ParticleSet<D>& ps, bool global) {
  if (all_.size() != ps.size()) all_ = all_indices(ps.size());  // kept: no allocation per step
  GridBounds<D> b = NeighbourGrid<D>::bounds(ps, all_);
  if (!global) {
    std::vector<double> m(2 * D + 1);
    for (int d = 0; d < D; ++d) {
      m[d] = -b.lo[d];
      m[D + d] = b.hi[d];
    }
    m[2 * D] = b.hmax;
    comm_.max(m);
    for (int d = 0; d < D; ++d) {
      b.lo[d] = -m[d];
      b.hi[d] = m[D + d];
    }
    b.hmax = m[2 * D];
  }
  bounds_ = b;
  grid_ = GridGeometry<D>::from_bounds(b);
}

template <int D>
void Decomposition<D>::rebalance(const ParticleSet<D>& ps, bool global) {
  int axis = 0;
  for (int d = 1; d < D; ++d)
    if (bounds_.hi[d] - bounds_.lo[d] > bounds_.hi[axis] - bounds_.lo[axis]) axis = d;
  std::vector<std::uint64_t> layer(static_cast<std::size_t>(grid_.dims[axis]), 0);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (!ps.inert(i)) ++layer[grid_.coord(ps.x[i], axis)];
  if (!global) comm_.sum(layer);
  const std::uint64_t total = std::accumulate(layer.begin(), layer.end(), std::uint64_t{0});
  const auto ranks = static_cast<std::uint64_t>(comm_.size());
  // Border r (between ranks r and r + 1) at the first layer before which at least (r + 1)/N of
  // the moving particles lie.
  std::vector<std::int64_t> cut(ranks - 1, kNoBorder);
  std::uint64_t before = 0;
  std::size_t r = 0;
  for (std::size_t c = 0; c < layer.size() && r < cut.size(); before += layer[c++])
    while (r < cut.size() && before * ranks >= (r + 1) * total) cut[r++] = static_cast<std::int64_t>(c);
  for (; r < cut.size(); ++r) cut[r] = static_cast<std::int64_t>(layer.size());
  if (axis != axis_ || cut != cut_) ++account_.rebalances;
  axis_ = axis;
  cut_ = cut;
}

template <int D>
void Decomposition<D>::append(ParticleSet<D>& ps, const std::vector<std::string>& received) {
  ParticleSet<D>& add = ps.additions();
  for (const std::string& bytes : received) unpack(bytes, add, key_);
  ps.compact();  // nothing queued for removal: appends
}

template <int D>
void Decomposition<D>::reorder(ParticleSet<D>& ps, const std::vector<std::size_t>& order) {
  ps.permute(order);
  std::vector<std::uint64_t> key(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) key[k] = key_[order[k]];
  key_.swap(key);
}

template <int D>
void Decomposition<D>::scatter(ParticleSet<D>& ps) {
  key_.resize(ps.size());
  std::iota(key_.begin(), key_.end(), std::uint64_t{0});
  find_grid(ps, true);
  cut_.assign(static_cast<std::size_t>(comm_.size() - 1), kNoBorder);
  rebalance(ps, true);
  std::vector<std::uint64_t> kept;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (owner(grid_.coord(ps.x[i], axis_)) != comm_.rank()) ps.queue_remove(i);
    else kept.push_back(key_[i]);
  key_.swap(kept);
  ps.compact();
}

template <int D>
void Decomposition<D>::begin_step(ParticleSet<D>& ps, long step, bool sort) {
  find_grid(ps, false);
  if (step % kRebalanceEvery == 0) rebalance(ps, false);
  std::vector<std::vector<std::uint32_t>> leaving(static_cast<std::size_t>(comm_.size()));
  std::vector<std::size_t> staying;
  staying.reserve(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const int r = owner(grid_.coord(ps.x[i], axis_));
    if (r == comm_.rank()) staying.push_back(i);
    else leaving[r].push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::string> send(leaving.size());
  for (std::size_t r = 0; r < leaving.size(); ++r)
    if (!leaving[r].empty()) send[r] = pack(ps, leaving[r], key_);
  account_.migrated += static_cast<long>(ps.size() - staying.size());
  const std::size_t before = ps.size();
  append(ps, comm_.exchange(send));
  if (staying.size() < before || ps.size() > before) {
    // One reorder: the staying particles (in key order) merged by key with the arrivals.
    std::vector<std::size_t> arrived(ps.size() - before), order(staying.size() + arrived.size());
    std::iota(arrived.begin(), arrived.end(), before);
    const auto by_key = [&](std::size_t a, std::size_t b) { return key_[a] < key_[b]; };
    std::sort(arrived.begin(), arrived.end(), by_key);
    std::merge(staying.begin(), staying.end(), arrived.begin(), arrived.end(), order.begin(), by_key);
    reorder(ps, order);
  }
  if (sort) sort_keys(ps);
  ++account_.steps;
}

template <int D>
void Decomposition<D>::sort_keys(ParticleSet<D>& ps) {
  // The one-process storage sort orders the particles by slot (inert, cell), cells in linear order
  // (axis 0 fastest), and within a slot by old key (NeighbourGrid::storage_order). Group the slots
  // in rows: the inert bit and the cell's coordinates along the axes slower than the cut axis.
  // Within a row the slots run along the cut axis, and a slab is one range of it, so a row holds
  // the ranks' slots in rank order. A particle's new key is the count of particles in the rows
  // before its own (all ranks), of the lower ranks' particles in its row, and of this rank's before
  // it in the row's (slot, old key) order: integer sums over the rows only.
  std::int64_t faster = 1, slower = 1;
  for (int d = 0; d < axis_; ++d) faster *= grid_.dims[d];
  for (int d = axis_ + 1; d < D; ++d) slower *= grid_.dims[d];
  const std::int64_t along = grid_.dims[axis_];
  const std::size_t n = ps.size(), rows = 2 * static_cast<std::size_t>(slower);
  std::vector<std::uint32_t> row(n);
  std::vector<std::uint64_t> place(n), count(rows, 0);  // place: the slot's position in its row
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t cell = grid_.cell_of(ps.x[i]);
    row[i] = static_cast<std::uint32_t>((ps.inert(i) ? slower : 0) + cell / (faster * along));
    place[i] = static_cast<std::uint64_t>(cell % (faster * along));
    ++count[row[i]];
  }
  std::vector<std::uint64_t> first = count, total = count;  // first: this rank's first key per row
  comm_.sum_below(first);
  comm_.sum(total);
  std::vector<std::size_t> local(rows + 1, 0);  // this rank's particles: where each row starts in `order`
  for (std::size_t r = 0, before = 0; r < rows; ++r) {
    first[r] += before;
    before += total[r];
    local[r + 1] = local[r] + count[r];
  }
  std::vector<std::size_t> order(n), fill(local.begin(), local.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order[fill[row[i]]++] = i;  // by row, each in old key order
  for (std::size_t r = 0; r < rows; ++r) {
    const auto begin = order.begin() + static_cast<std::ptrdiff_t>(local[r]), end = order.begin() + static_cast<std::ptrdiff_t>(local[r + 1]);
    std::sort(begin, end, [&](std::size_t a, std::size_t b) { return place[a] < place[b] || (place[a] == place[b] && a < b); });
    for (auto k = begin; k != end; ++k) key_[*k] = first[r] + static_cast<std::uint64_t>(k - begin);
  }
  reorder(ps, order);
}

template <int D>
void Decomposition<D>::add_halo(ParticleSet<D>& ps) {
  const auto ranks = static_cast<std::size_t>(comm_.size());
  own_ = ps.size();
  send_.assign(ranks, {});
  for (std::size_t i = 0; i < own_; ++i) {
    const std::int64_t c = grid_.coord(ps.x[i], axis_);
    for (std::size_t r = 0; r < ranks; ++r) {
      if (static_cast<int>(r) == comm_.rank()) continue;
      const std::int64_t from = r == 0 ? std::numeric_limits<std::int64_t>::min() : cut_[r - 1] - 1;
      const std::int64_t to = r + 1 == ranks ? kNoBorder : cut_[r];  // one layer past the slab's last
      if (c >= from && c <= to) send_[r].push_back(static_cast<std::uint32_t>(i));
    }
  }
  std::vector<std::string> send(ranks);
  for (std::size_t r = 0; r < ranks; ++r)
    if (!send_[r].empty()) send[r] = pack(ps, send_[r], key_);
  const std::vector<std::string> received = comm_.exchange(send);
  // Appended after this rank's own particles, each source's in its key order: a cell's particles
  // all come from one rank, so every cell keeps the one-process order (NeighbourGrid orders a
  // cell's particles by index).
  append(ps, received);
  recv_.assign(ranks, {});
  std::size_t at = own_;
  for (std::size_t r = 0; r < ranks; ++r) {
    std::uint64_t n = 0;
    if (!received[r].empty()) std::memcpy(&n, received[r].data(), sizeof n);
    for (std::uint64_t k = 0; k < n; ++k) recv_[r].push_back(static_cast<std::uint32_t>(at++));
  }
  account_.halo_particles += static_cast<long>(ps.size() - own_);
}

template <int D>
void Decomposition<D>::drop_halo(ParticleSet<D>& ps) {
  ps.truncate(own_);
  key_.resize(own_);
  own_ = kNoHalo;
  send_.clear();
  recv_.clear();
}

template <int D>
void Decomposition<D>::compact(ParticleSet<D>& ps, const std::vector<std::size_t>& queued_by) {
  const std::size_t own = own_ == kNoHalo ? ps.size() : own_;
  const std::size_t adds = ps.queued_additions();
  if (queued_by.size() != adds) throw std::logic_error("Decomposition::compact: an addition without the particle that queued it");
  const std::vector<std::uint8_t> sent = sent_flags(own);
  CompactionNotice notice;
  notice.particles = own;
  std::vector<std::size_t> removed;
  std::vector<std::uint64_t> kept;
  kept.reserve(own);
  for (std::size_t i = 0; i < own; ++i)
    if (ps.queued_for_removal(i)) {
      removed.push_back(i);
      notice.removed.push_back(key_[i]);
      account_.at_border += sent[i];
    } else {
      kept.push_back(key_[i]);
    }
  for (std::size_t k = 0; k < adds; ++k) {
    if (queued_by[k] >= own) throw std::logic_error("Decomposition::compact: an addition queued by a halo copy");
    notice.added.push_back({key_[queued_by[k]], k});
    account_.at_border += sent[queued_by[k]];
  }
  account_.removed += static_cast<long>(removed.size());
  account_.added += static_cast<long>(adds);
  std::vector<CompactionNotice> every_rank;
  for (const std::string& bytes : comm_.all_gather(encode(notice))) every_rank.push_back(decode(bytes));
  const CompactionKeys keys = compaction_keys(kept, notice.added, every_rank);
  if (own_ != kNoHalo) drop_halo(ps);  // clears the queued removals: queued again below
  for (const std::size_t i : removed) ps.queue_remove(i);
  // The one process gives its k-th addition the id next_id + k; every rank holds that next_id.
  const std::int64_t next_id = ps.next_id();
  if (adds > 0) {
    ParticleSet<D>& add = ps.additions();
    for (std::size_t k = 0; k < adds; ++k) add.id[k] = next_id + static_cast<std::int64_t>(keys.added[k] - keys.survivors);
  }
  ps.compact();
  ps.set_next_id(next_id + static_cast<std::int64_t>(keys.additions));
  key_ = keys.kept;
  key_.insert(key_.end(), keys.added.begin(), keys.added.end());
  if (!std::is_sorted(key_.begin(), key_.end())) reorder(ps, key_order(key_));  // a queue not in its queuers' order
}

template <int D>
std::vector<std::uint8_t> Decomposition<D>::sent_flags(std::size_t own) const {
  std::vector<std::uint8_t> sent(own, 0);
  for (const auto& to : send_)
    for (const std::uint32_t i : to) sent[i] = 1;
  return sent;
}

template <int D>
void Decomposition<D>::adopt(ParticleSet<D>& ps, ParticleSet<D> whole, const std::vector<std::size_t>& removed,
                             const std::vector<std::size_t>& queued_by) {
  const std::size_t own = own_ == kNoHalo ? ps.size() : own_;
  const std::vector<std::uint8_t> sent = sent_flags(own);
  // The keys before the compaction, 0..N-1, to this rank's index (none: another rank's particle).
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> mine(whole.size() + removed.size() - queued_by.size(), none);
  for (std::size_t i = 0; i < own; ++i) mine[key_[i]] = i;
  const auto count = [&](const std::vector<std::size_t>& keys, long& total) {
    for (const std::size_t k : keys)
      if (mine[k] != none) {
        ++total;
        account_.at_border += sent[mine[k]];
      }
  };
  count(removed, account_.removed);
  count(queued_by, account_.added);
  find_grid(whole, true);
  key_.clear();
  for (std::size_t i = 0; i < whole.size(); ++i)
    if (owner(grid_.coord(whole.x[i], axis_)) != comm_.rank()) whole.queue_remove(i);
    else key_.push_back(i);
  whole.compact();
  ps = std::move(whole);
  add_halo(ps);
}

template <int D>
ParticleSet<D> Decomposition<D>::gather(const ParticleSet<D>& owned) const {
  const std::size_t own = own_ == kNoHalo ? owned.size() : own_;
  const std::vector<std::string> all = comm_.all_gather(pack(owned, all_indices(own), key_));
  ParticleSet<D> out;
  if (owned.has_porous_fields()) out.add_porous_fields();  // the fields pack sent
  std::vector<std::uint64_t> keys;
  for (const std::string& bytes : all) unpack(bytes, out, keys);
  out.permute(key_order(keys));
  out.set_next_id(owned.next_id());
  return out;
}

template <int D>
DecompositionAccount Decomposition<D>::totals() const {
  std::vector<std::uint64_t> sums;
  for (const long n : {account_.migrated, account_.halo_particles, account_.removed, account_.added, account_.at_border})
    sums.push_back(static_cast<std::uint64_t>(n));
  comm_.sum(sums);
  DecompositionAccount a = account_;
  a.ranks = comm_.size();
  a.migrated = static_cast<long>(sums[0]);
  a.halo_particles = static_cast<long>(sums[1]);
  a.removed = static_cast<long>(sums[2]);
  a.added = static_cast<long>(sums[3]);
  a.at_border = static_cast<long>(sums[4]);
  return a;
}

template class Decomposition<2>;
template class Decomposition<3>;

}  // namespace sc

#include "core/particle_set.hpp"

#include <atomic>
#include <cstddef>
#include <cstring>
#include <omp.h>
#include <type_traits>
#include <string>

#include "core/checksum.hpp"

namespace sc {

namespace {

/// A layout value not given out before in this process (ParticleSet::layout).
std::uint64_t fresh_layout() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

}  // namespace

template <int D>
void ParticleSet<D>::relayout() {
  layout_ = fresh_layout();
  prefix_.reset();
}

template <int D>
void ParticleSet<D>::appended(Prefix before) {
  relayout();
  prefix_ = before;
}

template <int D>
std::size_t ParticleSet<D>::append() {
  const Prefix before{size(), layout_};
  visit_fields([](std::string_view, auto& field) { field.emplace_back(); });
  const std::size_t i = size() - 1;
  x[i].setZero(); v[i].setZero(); force[i].setZero();
  if (porous_fields_) pore_velocity[i].setZero();
  m[i] = 0.0; h[i] = 0.0; rho[i] = 1.0; rho0[i] = 1.0; p[i] = 0.0;
  phase[i] = static_cast<std::uint8_t>(Phase::Water);
  rough[i] = 0;
  id[i] = next_id_++;
  appended(before);
  return i;
}

template <int D>
void ParticleSet<D>::add_porous_fields() {
  if (porous_fields_) return;
  porous_fields_ = true;
  for (auto* f : {&absorbed, &emit_store, &saturation, &porosity, &capillary, &pore_pressure}) f->assign(size(), 0.0);
  pore_velocity.assign(size(), V::Zero());
}

template <int D>
void ParticleSet<D>::queue_remove(std::size_t i) {
  if (remove_flag_.size() != size()) remove_flag_.assign(size(), 0);
  remove_flag_[i] = 1;
}

template <int D>
ParticleSet<D>& ParticleSet<D>::additions() {
  if (additions_.empty()) additions_.emplace_back();
  ParticleSet& add = additions_.front();
  if (add.size() == 0) {  // a new queue (the set is kept empty between compactions, with its storage)
    add.next_id_ = next_id_;
    if (porous_fields_) add.add_porous_fields();
  }
  return add;
}

template <int D>
template <class F>
void ParticleSet<D>::visit_fields_with(const ParticleSet& other, F&& f) {
  visit_fields([&other, &f](std::string_view name, auto& field) {
    other.visit_fields([&](std::string_view other_name, const auto& src) {
      if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::decay_t<decltype(src)>>)
        if (name == other_name) f(field, src);
    });
  });
}

template <int D>
bool ParticleSet<D>::compact() {
  bool changed = false;
  if (remove_flag_.size() == size()) {
    thread_local std::vector<std::size_t> keep;  // kept between calls, as permute's scratch
    keep.clear();
    for (std::size_t i = 0; i < size(); ++i)
      if (!remove_flag_[i]) keep.push_back(i);
    if (keep.size() != size()) {
      permute(keep);  // a new layout
      changed = true;
    }
  }
  remove_flag_.clear();
  if (!additions_.empty() && additions_.front().size() > 0) {
    const Prefix before{size(), layout_};
    ParticleSet& add = additions_.front();
    visit_fields_with(add, [](auto& field, const auto& src) { field.insert(field.end(), src.begin(), src.end()); });
    next_id_ = add.next_id_;
    add.truncate(0);
    appended(before);
    changed = true;
  }
  return changed;
}

template <int D>
void ParticleSet<D>::permute(const std::vector<std::size_t>& order) {
  // The order's longest tail that takes one contiguous block of particles (the fixed walls a
  // decomposed run keeps after its moving particles, shifted by the migrations) moves as one block;
  // the particles before it are gathered into a scratch buffer kept by the thread between calls
  // and copied back into the field's own storage. No allocation and no fresh pages per call (a
  // decomposed run reorders its particles at every step in which some migrate), and the fields
  // keep their capacity, so the halo appended after a reorder does not reallocate them.
  thread_local std::vector<std::byte> scratch;
  std::size_t tail = order.size();  // then: order[k] = order[tail] + (k - tail) for every k >= tail
  while (tail > 1 && order[tail - 1] == order[tail - 2] + 1) --tail;
  if (tail > 0) --tail;
  const std::size_t block = order.empty() ? 0 : order[tail];
  const auto gathered = static_cast<std::int64_t>(tail);
  visit_fields([&](std::string_view, auto& field) {
    constexpr std::size_t bytes = sizeof(typename std::decay_t<decltype(field)>::value_type);
    if (scratch.size() < tail * bytes) scratch.resize(tail * bytes);
    std::byte* out = scratch.data();
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < gathered; ++k) std::memcpy(out + k * bytes, static_cast<const void*>(&field[order[k]]), bytes);
    if (tail < order.size())
      std::memmove(static_cast<void*>(&field[tail]), static_cast<const void*>(&field[block]), (order.size() - tail) * bytes);
    field.resize(order.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < gathered; ++k) std::memcpy(static_cast<void*>(&field[k]), out + k * bytes, bytes);
  });
  relayout();
}

template <int D>
void ParticleSet<D>::truncate(std::size_t n) {
  if (n >= size()) return;
  visit_fields([n](std::string_view, auto& field) { field.resize(n); });
  remove_flag_.clear();
  if (prefix_ && prefix_->size == n) {
    layout_ = prefix_->layout;
    prefix_.reset();
  } else {
    relayout();
  }
}

template <int D>
void ParticleSet<D>::copy_from(const ParticleSet& other) {
  if (porous_fields_ != other.porous_fields_) {  // take other's fields, then copy them below
    ParticleSet fresh;
    if (other.porous_fields_) fresh.add_porous_fields();
    *this = std::move(fresh);
  }
  visit_fields_with(other, [](auto& field, const auto& src) { field.resize(src.size()); });
  // One parallel region for all fields (not one per field): each thread copies its share of
  // every field, without a barrier between the fields.
#pragma omp parallel
  visit_fields_with(other, [](auto& field, const auto& src) {
    const auto n = static_cast<std::int64_t>(src.size());
#pragma omp for schedule(static) nowait
    for (std::int64_t k = 0; k < n; ++k) field[k] = src[k];
  });
  remove_flag_ = other.remove_flag_;
  additions_ = other.additions_;
  next_id_ = other.next_id_;
  layout_ = other.layout_;
  prefix_ = other.prefix_;
}

template <int D>
void ParticleSet<D>::refresh_from(const ParticleSet& other) {
  const std::size_t n = other.size();
#pragma omp parallel
  {
    // This thread's share of the particles and, in it, the runs of particles to copy in full
    // (not inert in both sets); block copies, no barrier between the fields.
    const auto threads = static_cast<std::size_t>(omp_get_num_threads());
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t lo = n * t / threads, hi = n * (t + 1) / threads;
    thread_local std::vector<std::pair<std::size_t, std::size_t>> runs;  // kept between calls
    runs.clear();
    for (std::size_t k = lo; k < hi;) {
      const auto full = [&](std::size_t i) { return !(inert(i) && other.inert(i)); };
      if (!full(k)) {
        ++k;
        continue;
      }
      const std::size_t begin = k;
      while (k < hi && full(k)) ++k;
      runs.emplace_back(begin, k);
    }
    visit_fields_with(other, [&](auto& field, const auto& src) {
      const void* f = &src;
      if (f == &other.rho || f == &other.p)  // change at the walls too
        std::copy(src.begin() + lo, src.begin() + hi, field.begin() + lo);
      else
        for (const auto& [begin, end] : runs) std::copy(src.begin() + begin, src.begin() + end, field.begin() + begin);
    });
  }
  remove_flag_ = other.remove_flag_;
  additions_ = other.additions_;
  next_id_ = other.next_id_;
}

template <int D>
std::string ParticleSet<D>::checksum() const {
  return state_checksum<D>(std::span<const Vec<D>>(x.data(), size()), std::span<const Vec<D>>(v.data(), size()));
}

std::string_view phase_name(Phase p) {
  switch (p) {
    case Phase::Water: return "water";
    case Phase::Sand: return "sand";
    case Phase::Boundary: return "boundary";
  }
  return "unknown";
}

template class ParticleSet<2>;
template class ParticleSet<3>;

}  // namespace sc

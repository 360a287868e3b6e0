#include "core/effects/particles/particle_accounting.h"

namespace bleedsim {

void ParticleAccounting::emit(std::uint64_t step, std::uint64_t count) {
  if (count == 0) return;
  emitted_ += count;
  // A new id n takes slot n mod capacity from id n − capacity: anything older than the newest
  // `capacity` ids that still lived is overwritten.
  if (emitted_ > capacity_ && emitted_ - capacity_ > oldest_alive_) {
    overwritten_ += emitted_ - capacity_ - oldest_alive_;
    oldest_alive_ = emitted_ - capacity_;
  }
  batches_.push_back({step, emitted_});
  while (!batches_.empty() && batches_.front().end_id <= oldest_alive_) batches_.pop_front();
}

void ParticleAccounting::end_step(std::uint64_t step) {
  // A particle emitted at step s has lived step − s + 1 steps once `step` is done.
  while (!batches_.empty() && step + 1 - batches_.front().step >= lifetime_steps_) {
    expired_ += batches_.front().end_id - oldest_alive_;
    oldest_alive_ = batches_.front().end_id;
    batches_.pop_front();
  }
}

ParticleCounts ParticleAccounting::counts() const {
  return {emitted_, emitted_ - oldest_alive_, expired_, overwritten_};
}

ParticleCounts with_aspirated(ParticleCounts c, const AspiratedFates& f) {
  c.alive -= f.aspirated - f.expired - f.overwritten;
  c.expired -= f.expired;
  c.overwritten -= f.overwritten;
  c.aspirated = f.aspirated;
  return c;
}

}  // namespace bleedsim

#pragma once
// Where every emitted particle went: still alive, expired (lived its lifetime), overwritten (its
// ring-buffer slot was taken by a newer one while it lived), or aspirated (taken by the suction).
// Kept on the host from the emission counts alone, exactly, and from what the suction took, which
// the backend counts: emitted = alive + expired + overwritten + aspirated after every step.
#include <cstdint>
#include <deque>

#include "core/physics/particles.h"

namespace bleedsim {

struct ParticleCounts {
  std::uint64_t emitted = 0;
  std::uint64_t alive = 0;
  std::uint64_t expired = 0;
  std::uint64_t overwritten = 0;
  std::uint64_t aspirated = 0;  // a field's fifth element only in a scene with [suction]
};

// The counts from the ids alone (`by_id`: an aspirated particle still counted as its id's range
// has it, alive, then expired or overwritten) corrected by what became of the aspirated ones.
ParticleCounts with_aspirated(ParticleCounts by_id, const AspiratedFates& fates);

class ParticleAccounting {
 public:
  ParticleAccounting(std::uint64_t capacity, std::uint64_t lifetime_steps)
      : capacity_(capacity), lifetime_steps_(lifetime_steps) {}

  // `count` particles emitted at the start of `step`, with the next ids in order.
  void emit(std::uint64_t step, std::uint64_t count);
  // After `step` has aged every particle: those that reached their lifetime are gone.
  void end_step(std::uint64_t step);

  ParticleCounts counts() const;
  // Ids [oldest_alive, emitted) are the live particles: the ring buffer keeps ids in order and
  // every particle lives the same number of steps, so the live ones are always the newest.
  std::uint64_t oldest_alive() const { return oldest_alive_; }

 private:
  struct Batch {
    std::uint64_t step;    // when it was emitted
    std::uint64_t end_id;  // one past its last id
  };
  std::uint64_t capacity_;
  std::uint64_t lifetime_steps_;
  std::uint64_t emitted_ = 0;
  std::uint64_t oldest_alive_ = 0;
  std::uint64_t expired_ = 0;
  std::uint64_t overwritten_ = 0;
  std::deque<Batch> batches_;  // live batches, oldest first
};

}  // namespace bleedsim

#pragma once
// Where every emitted particle went: still alive, expired (lived its lifetime), or overwritten
// (its ring-buffer slot was taken by a newer one while it lived). Kept on the host from the
// emission counts alone, exactly: emitted = alive + expired + overwritten after every step.
#include <cstdint>
#include <deque>

namespace bleedsim {

struct ParticleCounts {
  std::uint64_t emitted = 0;
  std::uint64_t alive = 0;
  std::uint64_t expired = 0;
  std::uint64_t overwritten = 0;
};

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

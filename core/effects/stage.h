#pragma once
// A stage is one effect's work per frame. Stages are built from the scene (core/effects/pipeline.h): a
// stage the scene does not call for is never constructed, so it allocates and launches nothing.
// Its kind (core/effects/stage_kinds.h) declares the fields it writes and reads; it adds and
// fetches only those.
#include <cstddef>
#include <string>

#include "core/effects/stage_kinds.h"
#include "core/runtime/backend.h"
#include "core/scene/scene.h"
#include "core/scene/state.h"

namespace bleedsim {

class Stage {
 public:
  explicit Stage(const StageKind& kind) : kind_(kind), name_(kind.name) {}
  virtual ~Stage() = default;
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;

  const std::string& name() const { return name_; }
  // Backend memory this stage holds: its fields and its private buffers.
  std::size_t bytes() const { return bytes_; }

  // Computes this stage's part of frame state.frames_done.
  virtual void run(const Scene& scene, State& state, Backend& backend) = 0;

 protected:
  Buffer allocate(Backend& backend, std::size_t bytes);
  // Adds the field `name` to State as this stage's kind declares it, allocated on the backend: an
  // image covers the scene's panel, any other field is `elements` long. Throws std::logic_error for
  // a field the kind does not declare.
  Field& add_field(const Scene& scene, State& state, Backend& backend, const std::string& name, int elements = 0);
  // A field an earlier stage wrote, which this stage's kind reads in this scene. Throws
  // std::logic_error for a field the kind does not declare, or that is missing.
  const Field& input(const Scene& scene, const State& state, const std::string& name) const;
  // Runs a twin pair on the backend, counted as this stage's work (Backend::run).
  template <class... A>
  void launch(Backend& backend, const A&... a) const {
    backend.run(name_, a...);
  }

 private:
  const StageKind& kind_;
  std::string name_;
  std::size_t bytes_ = 0;
};

}  // namespace bleedsim

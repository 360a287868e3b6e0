#pragma once
// A stage is one effect's work per frame. Stages are built from the scene (core/effects/pipeline.h): a
// stage the scene does not call for is never constructed, so it allocates and launches nothing.
#include <cstddef>
#include <string>

#include "core/runtime/backend.h"
#include "core/runtime/scene.h"
#include "core/runtime/state.h"

namespace bleedsim {

// A field with one value (of `channels` components) per pixel of the scene's panel.
Field image_field(const Scene& scene, const char* name, ElementType type, int channels, const char* unit,
                  const char* description);

class Stage {
 public:
  explicit Stage(std::string name) : name_(std::move(name)) {}
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
  // Runs a twin pair on the backend, counted as this stage's work (Backend::run).
  template <class... A>
  void launch(Backend& backend, const A&... a) const {
    backend.run(name_, a...);
  }
  // Adds a field this stage writes to State, allocated on the backend.
  Field& add_field(State& state, Backend& backend, Field field);

 private:
  std::string name_;
  std::size_t bytes_ = 0;
};

}  // namespace bleedsim

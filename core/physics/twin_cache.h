#pragma once
// What a backend's twin keeps from one run of a stage's work to the next (the CUDA particle steps'
// graph): owned by the stage that runs the work, so it lives as long as the memory it refers to.
namespace bleedsim {

class TwinCache {
 public:
  virtual ~TwinCache() = default;
};

}  // namespace bleedsim

#include "core/effects/particles/splat_stage.h"

#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/stage.h"
#include "core/effects/surface/surface_stage.h"
#include "core/physics/splat.h"

namespace bleedsim {

// (particles/position, particles/age) => splat/thickness
// Each frame, in scenes with particles: the live particles splatted into a film of blood, in mm.
class SplatStage final : public Stage {
 public:
  SplatStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  SplatArgs args_{};
  Buffer units_;   // the fixed-point sum
  Buffer stamps_;  // its tiles' stamps
};
namespace {

std::size_t pixels(const Scene& scene) { return scene.domain.pixels().to<std::size_t>(); }

}  // namespace

SplatStage::SplatStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state,
                       Backend& backend)
    : Stage(kind),
      units_(allocate(backend, pixels(scene) * sizeof(std::uint64_t))),
      stamps_(allocate(backend, splat_tile_count(scene.domain.grid()) * sizeof(std::uint32_t))) {
  const Field& position = input(scene, state, "particles/position");
  const Field& age = input(scene, state, "particles/age");
  Field& thickness = add_field(scene, state, backend, "splat/thickness");
  const ParticleSettings& particles = resolved.get<ParticleSettings>();
  args_.lifetime = particles.lifetime;
  args_.splat = particles.splat;
  args_.position = position.data.as<const float>();
  args_.age = age.data.as<const std::uint32_t>();
  args_.capacity = scene.effects.get<ParticleParams>().capacity;
  args_.grid = scene.domain.grid();
  args_.units = units_.as<std::uint64_t>();
  args_.thickness_mm = thickness.data.as<float>();
  // The sum zero, as every frame leaves it; no tile stamped yet (the first frame's stamp is 1).
  backend.upload(units_.data(), std::vector<std::uint64_t>(pixels(scene), 0u).data(), units_.bytes());
  backend.upload(stamps_.data(), std::vector<std::uint32_t>(splat_tile_count(args_.grid), 0u).data(), stamps_.bytes());
  args_.tiles = {stamps_.as<std::uint32_t>(), splat_tiles_across(args_.grid), 0u};
  args_.surface = surface_map(scene, state);
}

MemoryParts SplatStage::memory_for(const Scene& scene, const Resolved&) {
  return {scene.domain.memory(sizeof(std::uint64_t) + sizeof(float)),
          {"scene.width_px", "the splat's tile stamps",
           Count(splat_tile_count(scene.domain.grid())) * sizeof(std::uint32_t)}};
}

void SplatStage::run(const Scene&, State& state, Backend& backend) {
  ++args_.tiles.now;
  if (!state.film_downsample) return launch(backend, args_);
  // The blur's downsample in the conversion's pass: the film is read back from registers, not memory.
  SplatArgs with_downsample = args_;
  with_downsample.downsample = *state.film_downsample;
  backend.run_shared({name(), "blur"}, with_downsample);
}

const StageKind& splat_stage_kind() {
  static const StageKind kind{
      "splat", "particles", declares<ParticleParams>,
      {image_field("splat/thickness", ElementType::f32, 1, "mm",
                   "thickness of the film of blood the particles make: each one's volume spread over its splat "
                   "radius")},
      [](const Scene& s) {
        std::vector<std::string> reads{"particles/position", "particles/age"};
        for (const std::string& field : surface_fields(s)) reads.push_back(field);
        return reads;
      },
      SplatStage::memory_for, make_stage<SplatStage>};
  return kind;
}

}  // namespace bleedsim

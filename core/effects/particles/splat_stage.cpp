#include "core/effects/particles/splat_stage.h"

#include <vector>

#include "core/effects/particles/particle_model.h"
#include "core/effects/surface/surface_stage.h"
#include "core/physics/splat.h"

namespace bleedsim {
namespace {

std::size_t pixels(const Scene& scene) { return scene.domain.pixels().to<std::size_t>(); }

}  // namespace

SplatModel make_splat_model(const ParticleParams& p, const Domain& domain) {
  const double r = p.splat_radius_mm > 0.0 ? p.splat_radius_mm : p.diameter_mm;
  const double pixel_area_mm2 = domain.width_mm / domain.width_px * (domain.height_mm / domain.height_px);
  SplatModel s{};
  s.radius_mm = float(r);
  s.radius_sq = float(r * r);
  s.units_per_mm3 = float(double(kSplatUnitsPerMm) / pixel_area_mm2);
  s.particle_volume_mm3 = float(p.particle_volume_mm3);
  return s;
}

SplatStage::SplatStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      units_(allocate(backend, pixels(scene) * sizeof(std::uint64_t))),
      stamps_(allocate(backend, splat_tile_count(scene.domain.grid()) * sizeof(std::uint32_t))) {
  const Field& position = input(scene, state, "particles/position");
  const Field& age = input(scene, state, "particles/age");
  Field& thickness = add_field(scene, state, backend, "splat/thickness");
  args_.lifetime = particle_lifetime(scene);
  args_.splat = make_splat_model(*scene.particles, scene.domain);
  args_.position = position.data.as<const float>();
  args_.age = age.data.as<const std::uint32_t>();
  args_.capacity = scene.particles->capacity;
  args_.grid = scene.domain.grid();
  args_.units = units_.as<std::uint64_t>();
  args_.thickness_mm = thickness.data.as<float>();
  // The sum zero, as every frame leaves it; no tile stamped yet (the first frame's stamp is 1).
  backend.upload(units_.data(), std::vector<std::uint64_t>(pixels(scene), 0u).data(), units_.bytes());
  backend.upload(stamps_.data(), std::vector<std::uint32_t>(splat_tile_count(args_.grid), 0u).data(), stamps_.bytes());
  args_.tiles = {stamps_.as<std::uint32_t>(), splat_tiles_across(args_.grid), 0u};
  args_.surface = surface_map(scene, state);
}

MemoryParts SplatStage::memory_for(const Scene& scene) {
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

}  // namespace bleedsim

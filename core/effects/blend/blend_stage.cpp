#include "core/effects/blend/blend_stage.h"

#include "core/effects/blur/blur_params.h"
#include "core/effects/effect.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/effects/stage.h"
#include "core/effects/trail/trail_params.h"
#include "core/physics/optics_tables.h"
#include "core/physics/pixel_kernels.h"

namespace bleedsim {

// (tissue, spread/stain, the film: blur/thickness or splat/thickness, trail/residue) => frame
// Each frame: the blood's fields composited over the tissue into the RGBA8 frame, in linear light,
// lit by the endoscope's headlight in a scene with [optics]. Every scene has it: without effects
// the frame is the bare tissue.
class BlendStage final : public Stage {
 public:
  BlendStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  Buffer tissue_;       // the scene's tissue, uploaded once
  Buffer tables_;       // optics_tables(), uploaded once
  Buffer fixed_light_;  // with [optics]: the headlight's fixed light, made once
  BlendPixel work_{};
};
namespace {

std::size_t rgba_bytes(const Scene& scene) { return scene.domain.pixels().to<std::size_t>() * 4; }

}  // namespace

const char* blend_stain_field(const Scene& scene) {
  return scene.effects.has<SpreadParams>() ? "spread/stain" : nullptr;
}

const char* blend_film_field(const Scene& scene) {
  return scene.effects.has<BlurParams>()       ? "blur/thickness"
         : scene.effects.has<ParticleParams>() ? "splat/thickness"
                                               : nullptr;
}

const char* blend_residue_field(const Scene& scene) {
  return scene.effects.has<TrailParams>() ? "trail/residue" : nullptr;
}

BloodOptics blood_optics(const OpticsParams& o) {
  const BloodAbsorption a = blood_absorption(o);
  return {{float(a.per_mm[0]), float(a.per_mm[1]), float(a.per_mm[2])}, float(o.stain_depth_mm)};
}

Headlight headlight(const OpticsParams& o, const Domain& d) {
  return {float(d.width_mm / 2 + o.camera_x_mm), float(d.height_mm / 2 + o.camera_y_mm), float(o.camera_height_mm),
          o.falloff ? 1 : 0,   float(o.specular),  o.shininess, float(o.sheen), o.sheen_shininess};
}

BlendPixel blend_work(const Scene& scene, const float* tables, const std::uint8_t* tissue_rgba, const float* stain,
                      const float* film_mm, const float* residue_mm, std::uint8_t* frame_rgba,
                      const float* fixed_light) {
  const OpticsParams* lit = scene.effects.find<OpticsParams>();
  const OpticsParams optics = lit ? *lit : OpticsParams{};
  const PixelGrid grid = scene.domain.grid();
  return BlendPixel{tissue_rgba,
                    stain,
                    film_mm,
                    residue_mm,
                    transmission_table(tables),
                    srgb_tables(tables),
                    blood_optics(optics),
                    lit ? 1 : 0,
                    headlight(optics, scene.domain),
                    0.5f / grid.mm_per_px_x,
                    0.5f / grid.mm_per_px_y,
                    grid,
                    frame_rgba,
                    lit ? fixed_light : nullptr};
}

std::size_t fixed_light_bytes(const Scene& scene) {
  if (!scene.effects.has<OpticsParams>()) return 0;
  return scene.domain.pixels().to<std::size_t>() * kFixedLightChannels * sizeof(float);
}

void make_fixed_light(const Scene& scene, Backend& backend, const std::string& stage, float* fixed) {
  backend.run(stage,
              FixedLightPixel{headlight(scene.effects.get<OpticsParams>(), scene.domain), scene.domain.grid(), fixed});
}

BlendStage::BlendStage(const StageKind& kind, const Scene& scene, const Resolved&, State& state, Backend& backend)
    : Stage(kind),
      tissue_(allocate(backend, rgba_bytes(scene))),
      tables_(allocate(backend, kOpticsTableFloats * sizeof(float))),
      fixed_light_(allocate(backend, fixed_light_bytes(scene))) {
  const auto input_or_null = [&](const char* name) {
    return name ? input(scene, state, name).data.as<const float>() : nullptr;
  };
  Field& frame = add_field(scene, state, backend, "frame");
  if (scene.effects.has<OpticsParams>()) make_fixed_light(scene, backend, name(), fixed_light_.as<float>());
  const std::vector<float> tables = optics_tables();
  backend.upload(tables_.data(), tables.data(), tables.size() * sizeof(float));
  backend.upload(tissue_.data(), scene.tissue.rgba.data(), rgba_bytes(scene));
  work_ = blend_work(scene, tables_.as<const float>(), tissue_.as<const std::uint8_t>(),
                     input_or_null(blend_stain_field(scene)), input_or_null(blend_film_field(scene)),
                     input_or_null(blend_residue_field(scene)), frame.data.as<std::uint8_t>(),
                     fixed_light_.as<const float>());
}

MemoryParts BlendStage::memory_for(const Scene& scene, const Resolved&) {
  // The tissue and the frame, RGBA8; with [optics] the fixed light.
  const std::size_t per_pixel = 2 * 4 + (scene.effects.has<OpticsParams>() ? kFixedLightChannels * sizeof(float) : 0);
  return {scene.domain.memory(per_pixel),
          {"scene.width_px", "the blend's optical tables", Count(kOpticsTableFloats * sizeof(float))}};
}

void BlendStage::run(const Scene&, State& state, Backend& backend) {
  if (!state.trail_pass) return launch(backend, work_);
  backend.run_shared({"trail", name()}, pair_pixels(*state.trail_pass, work_));
  state.trail_pass.reset();
}

const Effect<OpticsParams>& optics_effect() {
  static const Effect<OpticsParams> row = [] {
    Effect<OpticsParams> e{optics_table};
    const auto reads = [](const Scene& s) {
      std::vector<std::string> fields;
      for (const char* field : {blend_stain_field(s), blend_film_field(s), blend_residue_field(s)})
        if (field) fields.push_back(field);
      return fields;
    };
    e.stages = {{"blend", "", [](const Scene&) { return true; },
                 {image_field("frame", ElementType::u8, 4, "sRGB 8-bit",
                              "the rendered frame: blood composited over the tissue in linear light (RGBA)")},
                 reads, BlendStage::memory_for, make_stage<BlendStage>}};
    return e;
  }();
  return row;
}

}  // namespace bleedsim

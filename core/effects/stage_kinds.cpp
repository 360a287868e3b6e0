#include "core/effects/stage_kinds.h"

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blur/blur_stage.h"
#include "core/effects/particles/particle_stage.h"
#include "core/effects/particles/splat_stage.h"
#include "core/effects/spread/spread_stage.h"
#include "core/effects/surface/surface_stage.h"
#include "core/effects/trail/trail_stage.h"

namespace bleedsim {
namespace {

// A field with one value (of `channels` components) per pixel of the panel.
FieldLayout image(const char* name, ElementType type, int channels, const char* unit, const char* description) {
  FieldLayout field;
  field.name = name;
  field.type = type;
  field.channels = channels;
  field.unit = unit;
  field.description = description;
  return field;
}

// A field of one row of elements (ring-buffer slots, or counters); `on_request`: written to files
// only when the scene lists it.
FieldLayout elements(const char* name, ElementType type, int channels, bool on_request, const char* unit,
                     const char* description) {
  FieldLayout field = image(name, type, channels, unit, description);
  field.image = false;
  field.on_request = on_request;
  return field;
}

std::vector<std::string> no_fields(const Scene&) { return {}; }

// An image field written to files only when the scene lists it: constants of the run.
FieldLayout on_request(FieldLayout field) {
  field.on_request = true;
  return field;
}

template <class S>
std::unique_ptr<Stage> make(const StageKind& kind, const Scene& scene, State& state, Backend& backend) {
  return std::make_unique<S>(kind, scene, state, backend);
}

}  // namespace

const FieldLayout* StageKind::written(const std::string& field) const {
  for (const FieldLayout& layout : writes)
    if (layout.name == field) return &layout;
  return nullptr;
}

const std::vector<StageKind>& stage_kinds() {
  static const std::vector<StageKind> kinds = {
      {"surface", "tissue", [](const Scene& s) { return s.mesh != nullptr; },
       {on_request(image("surface/frame", ElementType::f32, kSurfaceFrameChannels, "mm/mm",
                         "the tissue mesh's map from panel to surface mm at each texel, (a, b, c): a panel step "
                         "(dx, dy) goes (a dx + b dy, c dy) on the surface; and 1 where a triangle covers the texel")),
        on_request(image("surface/gravity", ElementType::f32, kSurfaceGravityChannels, "mm/s²",
                         "gravity along the tissue mesh's surface at each texel, in the frame of surface/frame"))},
       no_fields, SurfaceStage::memory_for, make<SurfaceStage>},
      {"spread", "spread", [](const Scene& s) { return s.spread.has_value(); },
       {image("spread/stain", ElementType::f32, 1, "1",
              "radial-spread stain: the share of a full stain (report 2.2.1), drawn as stain_depth_mm of blood")},
       surface_fields, SpreadStage::memory_for, make<SpreadStage>},
      {"particles", "particles", [](const Scene& s) { return s.particles.has_value(); },
       {elements("particles/position", ElementType::f32, 2, true, "mm", "centre of each ring-buffer slot's particle"),
        elements("particles/velocity", ElementType::f32, 2, true, "mm/s", "velocity of each slot's particle"),
        elements("particles/age", ElementType::u32, 1, true, "steps",
                 "steps each slot's particle has lived; a slot holds a live particle while its age is below the "
                 "lifetime (an aspirated particle's age has its top bit, 2^31, set)"),
        elements("particles/accounting", ElementType::u64, 1, false, "particles",
                 "emitted, alive, expired, overwritten, and with [suction] aspirated: emitted = alive + expired + "
                 "overwritten (+ aspirated)")},
       surface_fields, ParticleStage::memory_for, make<ParticleStage>},
      {"splat", "particles", [](const Scene& s) { return s.particles.has_value(); },
       {image("splat/thickness", ElementType::f32, 1, "mm",
              "thickness of the film of blood the particles make: each one's volume spread over its splat radius")},
       [](const Scene& s) {
         std::vector<std::string> reads{"particles/position", "particles/age"};
         for (const std::string& field : surface_fields(s)) reads.push_back(field);
         return reads;
       },
       SplatStage::memory_for, make<SplatStage>},
      {"blur", "blur", [](const Scene& s) { return s.blur.has_value(); },
       {image("blur/thickness", ElementType::f32, 1, "mm",
              "the film of blood downsampled, blurred and upsampled: what the blend lays over the tissue")},
       [](const Scene&) { return std::vector<std::string>{"splat/thickness"}; }, BlurStage::memory_for,
       make<BlurStage>},
      {"trail", "trail", [](const Scene& s) { return s.trail.has_value(); },
       {image("trail/residue", ElementType::f32, 1, "mm",
              "the blood that ran over each pixel, left behind as an equivalent film and drying")},
       [](const Scene&) { return std::vector<std::string>{"splat/thickness"}; }, TrailStage::memory_for,
       make<TrailStage>},
      {"blend", "", [](const Scene&) { return true; },
       {image("frame", ElementType::u8, 4, "sRGB 8-bit",
              "the rendered frame: blood composited over the tissue in linear light (RGBA)")},
       [](const Scene& s) {
         std::vector<std::string> reads;
         for (const char* field : {blend_stain_field(s), blend_film_field(s), blend_residue_field(s)})
           if (field) reads.push_back(field);
         return reads;
       },
       BlendStage::memory_for, make<BlendStage>},
  };
  return kinds;
}

const StageKind* stage_writing(const std::string& field) {
  for (const StageKind& kind : stage_kinds())
    if (kind.written(field)) return &kind;
  return nullptr;
}

}  // namespace bleedsim

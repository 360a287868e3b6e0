#pragma once
// The frame: the blood's fields composited over the tissue (docs/optics.md). What the blend stage
// (blend_stage.cpp, with the optics' row) reads and makes, which the study and the tests ask too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/effects/blend/optics_params.h"
#include "core/physics/blend.h"
#include "core/runtime/backend.h"
#include "core/scene/scene.h"

namespace bleedsim {

// What the blend lays over the tissue, by field name, or null where the scene has none of it: the
// stain, spread/stain with [spread]; the film of blood, blur/thickness with [blur], else
// splat/thickness with [particles]; the residue, trail/residue with [trail].
const char* blend_stain_field(const Scene& scene);
const char* blend_film_field(const Scene& scene);
const char* blend_residue_field(const Scene& scene);

// The blood as an absorber, and the headlight, for a scene's optics (the defaults without [optics]).
BloodOptics blood_optics(const OpticsParams& optics);
Headlight headlight(const OpticsParams& optics, const Domain& domain);

// The blend's work over a scene's fields (stain, film and residue may be null), reading the
// tables at `tables` (optics_tables(), on the backend that runs it) and, with [optics], the fixed
// light at `fixed_light` (make_fixed_light's; null: computed pixel by pixel, the same bytes):
// what BlendStage runs.
BlendPixel blend_work(const Scene& scene, const float* tables, const std::uint8_t* tissue_rgba, const float* stain,
                      const float* film_mm, const float* residue_mm, std::uint8_t* frame_rgba,
                      const float* fixed_light = nullptr);

// The headlight's fixed light (FixedLightPixel) of a scene with [optics]: its bytes (0 without),
// and its making into `fixed` on the backend, a run counted under `stage`.
std::size_t fixed_light_bytes(const Scene& scene);
void make_fixed_light(const Scene& scene, Backend& backend, const std::string& stage, float* fixed);

}  // namespace bleedsim

#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "core/effects/blend/optics_params.h"
#include "core/effects/stage.h"
#include "core/physics/blend.h"

namespace bleedsim {

// (tissue, spread/stain, the film: blur/thickness or splat/thickness, trail/residue) => frame
// Each frame: the blood's fields composited over the tissue into the RGBA8 frame, in linear light,
// lit by the endoscope's headlight in a scene with [optics]. Every scene has it: without effects
// the frame is the bare tissue.
class BlendStage final : public Stage {
 public:
  BlendStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend);
  static MemoryParts memory_for(const Scene& scene);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  Buffer tissue_;  // the scene's tissue, uploaded once
  Buffer tables_;  // optics_tables(), uploaded once
  Buffer fixed_light_;  // with [optics]: the headlight's fixed light, made once
  BlendPixel work_{};
};

// What the blend lays over the tissue, by field name, or null where the scene has none of it: the
// stain, spread/stain with [spread]; the film of blood, blur/thickness with [blur], else
// splat/thickness with [particles]; the residue, trail/residue with [trail].
const char* blend_stain_field(const Scene& scene);
const char* blend_film_field(const Scene& scene);
const char* blend_residue_field(const Scene& scene);

// The tables the blend reads, one after another, made on the host in double and rounded once to
// float: sRGB's 256 bytes in linear light; the 255 boundaries between them (the linear value of
// code (k + ½)/255); exp(−k / kTransmissionStepsPerUnit) for the Beer–Lambert transmission; the
// encoding's bucket starts (SrgbTables).
constexpr std::size_t kOpticsTableFloats = kSrgbBytes + (kSrgbBytes - 1) + kTransmissionEntries + kSrgbBuckets;
// The sRGB tables within optics_tables() at `tables`.
SrgbTables srgb_tables(const float* tables);
std::vector<float> optics_tables();

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

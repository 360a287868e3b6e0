#include "core/effects/blend/blend_stage.h"

#include <cmath>

#include "core/physics/pixel_kernels.h"

namespace bleedsim {
namespace {

std::size_t rgba_bytes(const Scene& scene) { return scene.domain.pixels().to<std::size_t>() * 4; }

// IEC 61966-2-1: the sRGB code value c ∈ [0, 1] as linear light.
double linear_from_code(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

}  // namespace

const char* blend_stain_field(const Scene& scene) { return scene.spread ? "spread/stain" : nullptr; }

const char* blend_film_field(const Scene& scene) {
  return scene.blur ? "blur/thickness" : scene.particles ? "splat/thickness" : nullptr;
}

const char* blend_residue_field(const Scene& scene) { return scene.trail ? "trail/residue" : nullptr; }

std::vector<float> optics_tables() {
  std::vector<float> t;
  for (int b = 0; b < kSrgbBytes; ++b) t.push_back(float(linear_from_code(b / 255.0)));
  for (int k = 0; k + 1 < kSrgbBytes; ++k) t.push_back(float(linear_from_code((k + 0.5) / 255.0)));
  for (int k = 0; k < kTransmissionEntries; ++k) t.push_back(float(std::exp(-double(k) / kTransmissionStepsPerUnit)));
  // Indexed, not through a pointer: the push_back below may move the table.
  const std::size_t boundaries = kSrgbBytes;
  int reached = 0;
  for (int k = 0; k < kSrgbBuckets; ++k) {
    const float start = float(k) / float(kSrgbBuckets);  // exact
    while (reached < kSrgbBytes - 1 && t[boundaries + reached] <= start) ++reached;
    t.push_back(float(reached));
  }
  return t;
}

SrgbTables srgb_tables(const float* tables) {
  return {tables, tables + kSrgbBytes, tables + 2 * kSrgbBytes - 1 + kTransmissionEntries};
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
  const OpticsParams optics = scene.optics.value_or(OpticsParams{});
  const PixelGrid grid = scene.domain.grid();
  return BlendPixel{tissue_rgba,
                    stain,
                    film_mm,
                    residue_mm,
                    tables + 2 * kSrgbBytes - 1,
                    srgb_tables(tables),
                    blood_optics(optics),
                    scene.optics ? 1 : 0,
                    headlight(optics, scene.domain),
                    0.5f / grid.mm_per_px_x,
                    0.5f / grid.mm_per_px_y,
                    grid,
                    frame_rgba,
                    scene.optics ? fixed_light : nullptr};
}

std::size_t fixed_light_bytes(const Scene& scene) {
  return scene.optics ? scene.domain.pixels().to<std::size_t>() * kFixedLightChannels * sizeof(float) : 0;
}

void make_fixed_light(const Scene& scene, Backend& backend, const std::string& stage, float* fixed) {
  backend.run(stage, FixedLightPixel{headlight(*scene.optics, scene.domain), scene.domain.grid(), fixed});
}

BlendStage::BlendStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      tissue_(allocate(backend, rgba_bytes(scene))),
      tables_(allocate(backend, kOpticsTableFloats * sizeof(float))),
      fixed_light_(allocate(backend, fixed_light_bytes(scene))) {
  const auto input_or_null = [&](const char* name) {
    return name ? input(scene, state, name).data.as<const float>() : nullptr;
  };
  Field& frame = add_field(scene, state, backend, "frame");
  if (scene.optics) make_fixed_light(scene, backend, name(), fixed_light_.as<float>());
  const std::vector<float> tables = optics_tables();
  backend.upload(tables_.data(), tables.data(), tables.size() * sizeof(float));
  backend.upload(tissue_.data(), scene.tissue.rgba.data(), rgba_bytes(scene));
  work_ = blend_work(scene, tables_.as<const float>(), tissue_.as<const std::uint8_t>(),
                     input_or_null(blend_stain_field(scene)), input_or_null(blend_film_field(scene)),
                     input_or_null(blend_residue_field(scene)), frame.data.as<std::uint8_t>(),
                     fixed_light_.as<const float>());
}

MemoryParts BlendStage::memory_for(const Scene& scene) {
  // The tissue and the frame, RGBA8; with [optics] the fixed light.
  const std::size_t per_pixel = 2 * 4 + (scene.optics ? kFixedLightChannels * sizeof(float) : 0);
  return {scene.domain.memory(per_pixel),
          {"scene.width_px", "the blend's optical tables", Count(kOpticsTableFloats * sizeof(float))}};
}

void BlendStage::run(const Scene&, State& state, Backend& backend) {
  if (!state.trail_pass) return launch(backend, work_);
  backend.run_shared({"trail", name()}, pair_pixels(*state.trail_pass, work_));
  state.trail_pass.reset();
}

}  // namespace bleedsim

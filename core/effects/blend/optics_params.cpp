#include "core/effects/blend/optics_params.h"

namespace bleedsim {
namespace {

using P = OpticsParams;

// Haemoglobin's molar extinction coefficient ε (cm⁻¹/M) at the wavelengths that stand for the
// three channels: S. Prahl, "Optical absorption of hemoglobin" (omlc.org/spectra/hemoglobin),
// compiled from W. B. Gratzer and N. Kollias. Red is 650 nm, where a thick film still lets light
// through, as a camera's red channel sees it; green 550 nm; blue 450 nm (docs/optics.md).
struct Extinction {
  double oxygenated, deoxygenated;
};
constexpr Extinction kExtinction[3] = {{368.0, 3750.12}, {43016.0, 53412.0}, {62816.0, 103292.0}};
constexpr double kHaemoglobinGramsPerMole = 64500.0;

}  // namespace

BloodAbsorption blood_absorption(const OpticsParams& o) {
  BloodAbsorption a{};
  const double molar = o.haemoglobin_g_per_l / kHaemoglobinGramsPerMole;  // mol/L
  for (int c = 0; c < 3; ++c) {
    const Extinction& e = kExtinction[c];
    const double epsilon = o.oxygen_saturation * e.oxygenated + (1.0 - o.oxygen_saturation) * e.deoxygenated;
    a.per_mm[c] = 2.303 * epsilon * molar / 10.0;  // 1/cm to 1/mm
  }
  return a;
}

const ParamTable<OpticsParams>& optics_table() {
  using T = ParamType;
  static const ParamTable<P> table{
      "optics",
      "declares the endoscope's headlight: the light falling off from the lens, the blood's highlights and "
      "the tissue's sheen; and sets what the blood absorbs (every scene draws its blood so, with the defaults "
      "when it has no [optics])",
      {{"oxygen_saturation", T::number, BLEEDSIM_MEMBER(P, oxygen_saturation), "", {0, 1},
        "of the blood's haemoglobin: arterial about 0.98, venous 0.75"},
       {"haemoglobin_g_per_l", T::number, BLEEDSIM_MEMBER(P, haemoglobin_g_per_l), "g/L", {0, 400, true},
        "haemoglobin in whole blood"},
       {"stain_depth_mm", T::number, BLEEDSIM_MEMBER(P, stain_depth_mm), "mm", {0, 10},
        "the film of blood a full stain holds in the tissue: the stain is drawn as that much blood"},
       {"camera_mm", T::vector, BLEEDSIM_VECTOR(P, camera_x_mm, camera_y_mm), "mm", {-1e4, 1e4},
        "the endoscope's tip (its lens and light) over the panel, from the panel's centre"},
       {"camera_height_mm", T::number, BLEEDSIM_MEMBER(P, camera_height_mm), "mm", {0, 1e4, true},
        "the tip's height above the panel"},
       {"falloff", T::flag, BLEEDSIM_MEMBER(P, falloff), "", {},
        "the light falls off from the point under the tip as a point source's, cos θ / r²"},
       {"specular", T::number, BLEEDSIM_MEMBER(P, specular), "", {0, 100},
        "the blood's highlight at its peak, in linear light (1: the light's white); 0: none"},
       {"shininess", T::integer, BLEEDSIM_MEMBER(P, shininess), "", {1, 4096},
        "the highlight's lobe exponent: higher is a smaller, sharper highlight"},
       {"sheen", T::number, BLEEDSIM_MEMBER(P, sheen), "", {0, 100},
        "the wet tissue's own highlight at its peak, in linear light; 0: none"},
       {"sheen_shininess", T::integer, BLEEDSIM_MEMBER(P, sheen_shininess), "", {1, 4096},
        "the sheen's lobe exponent"}},
      {}};
  return table;
}

}  // namespace bleedsim

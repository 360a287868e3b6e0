#pragma once
// The endoscope's view (docs/optics.md): what the blood absorbs, and the headlight at the lens.
#include "core/runtime/params.h"

namespace bleedsim {

template <class P>
struct Effect;

// Every scene draws its blood with the absorption below (the defaults when it has no [optics]);
// a scene with [optics] is also lit by the endoscope's headlight, with its falloff and highlights.
struct OpticsParams {
  double oxygen_saturation = 0.75;     // of the blood's haemoglobin: arterial about 0.98, venous 0.75
  double haemoglobin_g_per_l = 150.0;  // whole blood
  double stain_depth_mm = 0.04;        // the film of blood a full stain holds in the tissue
  double camera_x_mm = 0.0;            // the endoscope's tip, from the panel's centre ...
  double camera_y_mm = 0.0;
  double camera_height_mm = 20.0;      // ... and above the panel
  bool falloff = true;                 // the headlight falls off as a point source's
  double specular = 1.0;               // the blood's highlight at its peak (linear light)
  int shininess = 256;                 // its lobe's exponent
  double sheen = 0.1;                  // the wet tissue's own highlight at its peak
  int sheen_shininess = 32;
};

const ParamTable<OpticsParams>& optics_table();
// Its row: the blend stage, which every scene runs and [optics] lights (blend_stage.cpp).
const Effect<OpticsParams>& optics_effect();

// μ_c, whole blood's absorption (1/mm) for red, green and blue (650, 550 and 450 nm): haemoglobin's
// molar extinction (Prahl, from Gratzer and Kollias) at the saturation, 2.303 · ε · c / 64,500 g/mol.
struct BloodAbsorption {
  double per_mm[3];
};
BloodAbsorption blood_absorption(const OpticsParams& optics);

}  // namespace bleedsim

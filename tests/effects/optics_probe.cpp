// Prints what the blend draws for a film of whole blood over one mucosa colour, for the colour
// targets' independent check (tests/effects/optics_colours.py): one line per case,
// "saturation thickness_mm r g b". Usage: optics_probe R G B saturation... -- thickness_mm...
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blend/optics_params.h"
#include "core/physics/optics_tables.h"

int main(int argc, char** argv) {
  using namespace bleedsim;
  std::vector<double> saturations, thicknesses;
  bool after_dashes = false;
  for (int a = 4; a < argc; ++a) {
    if (std::strcmp(argv[a], "--") == 0) {
      after_dashes = true;
      continue;
    }
    (after_dashes ? thicknesses : saturations).push_back(std::atof(argv[a]));
  }
  if (argc < 4 || saturations.empty() || thicknesses.empty()) {
    std::fprintf(stderr, "usage: optics_probe R G B saturation... -- thickness_mm...\n");
    return 2;
  }
  const std::uint8_t tissue[4] = {std::uint8_t(std::atoi(argv[1])), std::uint8_t(std::atoi(argv[2])),
                                  std::uint8_t(std::atoi(argv[3])), 255};
  const std::vector<float> tables = optics_tables();
  for (const double s : saturations)
    for (const double h : thicknesses) {
      Scene scene;
      scene.domain = Domain{1, 1, 1.0, 1.0};
      OpticsParams optics;
      optics.oxygen_saturation = s;
      optics.falloff = false;
      optics.specular = optics.sheen = 0.0;
      scene.effects.set(optics);
      const float film = float(h);
      std::uint8_t frame[4];
      blend_work(scene, tables.data(), tissue, nullptr, &film, nullptr, frame)(0, 0);
      std::printf("%g %g %d %d %d\n", s, h, frame[0], frame[1], frame[2]);
    }
  return 0;
}

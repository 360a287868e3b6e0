#pragma once
// The tables only a scenario file has, beside the Scene's and the effects': [tissue] (the texture
// and the mesh it covers), [view] (the endoscope's camera) and [output] (output_spec.h); and every
// table a file may hold, in order, as people read them.
#include <string>
#include <vector>

#include "core/io/output_spec.h"
#include "core/mesh/mesh_surface.h"
#include "core/mesh/view_render.h"
#include "core/runtime/params.h"

namespace bleedsim {

// [tissue]: the texture a file names, or none for the procedural mucosa; and the mesh it covers,
// with where the mesh sits in the device frame, or none for the flat panel.
struct TissueFile {
  std::string texture;
  std::string mesh;
  MeshPlacement placement;
};

const ParamTable<TissueFile>& tissue_table();
const ParamTable<ViewCamera>& view_table();

// Every table a scenario may hold, in the order docs/scenario-format.md lists them: what
// `bleedsim params` prints and the docs' generated tables show.
std::vector<TableView> scenario_tables();
// The parameter "table.key" ("particles.substeps") of those tables; std::out_of_range when none is.
const ParamView& scenario_param(const std::string& key);

}  // namespace bleedsim

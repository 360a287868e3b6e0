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

// A key scenario files once held, and what became of it: an old file's key is refused saying so
// (docs/scenario-format.md, "Former keys", is written from this table).
struct FormerKey {
  const char* table;        // "particles", or "cut" for each [[cut]]
  const char* key;          // "rate_per_s"
  const char* replacement;  // the key of the same table that took its place; empty when none did
  const char* what;         // what the replacement means and how the old value maps to it, or why it went
  const char* since;        // "2026-11-25, issue 12"
  const char* commit;       // the commit that made the change
};
const std::vector<FormerKey>& former_keys();
// The former key `key` of `table`, or null when it was never one.
const FormerKey* find_former_key(const std::string& table, const std::string& key);

}  // namespace bleedsim

#include "core/io/scenario_tables.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "core/effects/cuts.h"
#include "core/effects/effect_list.h"
#include "core/effects/stage_kinds.h"
#include "core/effects/tips.h"
#include "core/haptics/haptic_params.h"
#include "core/scene/scene.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

// The placement's keys say where a mesh goes: without one they say nothing, and are refused.
ParamProblem placement_needs_a_mesh(TissueFile& tissue, const Written& written, const Scene&) {
  if (!tissue.mesh.empty()) return {};
  for (const char* key : {"mesh_position_mm", "mesh_rotation_deg", "mesh_scale"})
    if (written.has(key)) return {key, "places a tissue mesh, and this scene names none (tissue.mesh)"};
  return {};
}

// A view draws the mesh; its camera must look somewhere, with an up that is not its view.
ParamProblem camera_looks_somewhere(const ViewCamera& camera, const Scene&) {
  try {
    check_view_camera(camera);
  } catch (const std::invalid_argument& e) {
    return {"look_at_mm", e.what()};
  }
  return {};
}

// The output folder defaults to out/<name>; the fields listed must be ones this scene makes.
ParamProblem resolve_output(OutputSpec& out, const Written& written, const Scene& scene) {
  if (!written.has("dir")) out.dir = "out/" + scene.name;
  if (out.dir.empty()) return {"dir", "must not be empty"};
  for (const fs::path& part : fs::path(out.dir))
    if (part.string().size() > kMaxFileName)
      return {"dir", "holds a name of " + std::to_string(part.string().size()) + " characters; a file system holds " +
                         "at most " + std::to_string(kMaxFileName)};
  for (std::size_t i = 0; i < out.fields.size(); ++i) {
    const std::string key = "fields[" + std::to_string(i) + "]";
    const std::string& name = out.fields[i];
    const StageKind* writer = name == "frame" ? nullptr : stage_writing(name);
    if (!writer) {
      std::string all;
      for (const StageKind& kind : stage_kinds())
        for (const FieldLayout& field : kind.writes)
          if (field.name != "frame") all += (all.empty() ? "" : ", ") + field.name;
      return {key, "unknown field '" + name + "' (known: " + all + "; the frame is always written)"};
    }
    if (!writer->wanted(scene) && std::string(writer->table) == "tissue")
      return {key, "'" + name + "' needs a tissue mesh (tissue.mesh), which this scene does not have"};
    if (!writer->wanted(scene))
      return {key, "'" + name + "' needs the [" + writer->table + "] effect, which this scene does not declare"};
    if (std::find(out.fields.begin(), out.fields.begin() + std::ptrdiff_t(i), name) != out.fields.begin() + std::ptrdiff_t(i))
      return {key, "'" + name + "' is listed twice"};
  }
  return {};
}

}  // namespace

const ParamTable<TissueFile>& tissue_table() {
  using T = ParamType;
  using P = TissueFile;
  static const ParamTable<TissueFile> table{
      "tissue",
      "a PNG texture under the blood, and the mesh it covers; leave it out for a procedural mucosa on the flat panel",
      {{"texture", T::text, BLEEDSIM_MEMBER(P, texture), "", {},
        "a PNG file, relative to the scenario file; resampled to the panel's pixels", "none: a procedural mucosa"},
       {"mesh", T::text, BLEEDSIM_MEMBER(P, mesh), "", {},
        "a tissue mesh (OBJ, docs/mesh.md), relative to the scenario file: the panel is its texture, and blood "
        "runs on its surface",
        "none: the flat panel"},
       {"mesh_position_mm", T::vector3,
        BLEEDSIM_VECTOR3(P, placement.position_mm.x(), placement.position_mm.y(), placement.position_mm.z()), "mm",
        {-1e4, 1e4}, "where the mesh's origin sits in the device frame (x right, y up, z towards the user)"},
       {"mesh_rotation_deg", T::vector3,
        BLEEDSIM_VECTOR3(P, placement.rotation_deg.x(), placement.rotation_deg.y(), placement.rotation_deg.z()), "°",
        {-360, 360}, "the mesh turned about the device's x, then y, then z axis before it is moved"},
       {"mesh_scale", T::number, BLEEDSIM_MEMBER(P, placement.scale), "", {0, 1e3, true},
        "the mesh's units in mm: its points are multiplied by this before they are turned"}},
      {},
      placement_needs_a_mesh};
  return table;
}

const ParamTable<ViewCamera>& view_table() {
  using T = ParamType;
  using P = ViewCamera;
  static const ParamTable<ViewCamera> table{
      "view",
      "the tissue mesh drawn with its bleeding texture from an endoscope, beside each PNG frame "
      "(png/view_NNNNNN.png) and as view_contact_sheet.png; needs tissue.mesh",
      {{"eye_mm", T::vector3, BLEEDSIM_VECTOR3(P, eye_mm.x(), eye_mm.y(), eye_mm.z()), "mm", {-1e4, 1e4},
        "the endoscope's tip in the device frame (x right, y up, z towards the user)", nullptr, true},
       {"look_at_mm", T::vector3, BLEEDSIM_VECTOR3(P, look_at_mm.x(), look_at_mm.y(), look_at_mm.z()), "mm",
        {-1e4, 1e4}, "the point it looks at, the middle of the image", nullptr, true},
       {"up", T::vector3, BLEEDSIM_VECTOR3(P, up.x(), up.y(), up.z()), "", {-1e4, 1e4},
        "the direction that is up in the image; not along the view"},
       {"fov_y_deg", T::number, BLEEDSIM_MEMBER(P, fov_y_deg), "°", {0, 180, true},
        "the vertical field of view (under 180°)"},
       {"width_px", T::integer, BLEEDSIM_MEMBER(P, width_px), "px", {1, 16384}, "the view's width"},
       {"height_px", T::integer, BLEEDSIM_MEMBER(P, height_px), "px", {1, 16384}, "the view's height"}},
      {{"the camera looks somewhere (eye_mm is not look_at_mm), up is not along the view, fov_y_deg is "
        "under 180",
        camera_looks_somewhere}}};
  return table;
}

std::vector<TableView> scenario_tables() {
  std::vector<TableView> tables{describe(scene_table()), describe(tissue_table())};
  for (TableView& effect : effect_tables()) tables.push_back(std::move(effect));
  for (TableView table : {describe(haptic_table()), describe(cut_table()), describe(tip_table()),
                          describe(view_table()), describe(output_table())})
    tables.push_back(std::move(table));
  return tables;
}

const ParamView& scenario_param(const std::string& key) {
  static const std::vector<TableView> tables = scenario_tables();
  for (const TableView& table : tables)
    for (const ParamView& param : table.params)
      if (key == table.name + "." + param.key) return param;
  throw std::out_of_range("no scenario parameter '" + key + "'");
}

const std::vector<FormerKey>& former_keys() {
  // In table, then key order. Issue 12's model replaced particles counted per second by blood per mm
  // of wound, and a contact set by hand by one derived from the pile it must bear.
  static const std::vector<FormerKey> table = {
      {"cut", "rate_per_s", "flow_mm3_per_s_per_mm",
       "blood per second per mm of the cut's wound_mm, its particles that blood over particle_volume_mm3: "
       "rate_per_s × particle_volume_mm3 for a wound of 1 mm",
       "2026-11-25, issue 12", "25ce75c"},
      {"particles", "damping_per_s", "damping_ratio",
       "the contact's dashpot as a fraction of a pair's critical damping, not per second", "2026-11-25, issue 12",
       "25ce75c"},
      {"particles", "max_per_cell", "",
       "there is no cap per cell: every pair within range is summed, from both sides", "2026-11-25, issue 12",
       "25ce75c"},
      {"particles", "rate_per_s", "flow_mm3_per_s_per_mm",
       "the cuts' default blood per second per mm of wound, the particles that blood over particle_volume_mm3: "
       "rate_per_s × particle_volume_mm3 for a wound of 1 mm",
       "2026-11-25, issue 12", "25ce75c"},
      {"particles", "stiffness_per_s2", "compression",
       "the deepest pile's overlap as a fraction of the diameter; the contact's stiffness follows from it and "
       "design_depth_mm (docs/particles.md)",
       "2026-11-25, issue 12", "25ce75c"},
      {"particles", "volume_mm3_per_s", "flow_mm3_per_s_per_mm",
       "the cuts' default blood per second per mm of wound: volume_mm3_per_s for a wound of 1 mm", "2026-11-25, issue 12",
       "25ce75c"},
  };
  return table;
}

const FormerKey* find_former_key(const std::string& table, const std::string& key) {
  for (const FormerKey& former : former_keys())
    if (table == former.table && key == former.key) return &former;
  return nullptr;
}

const ParamTable<OutputSpec>& output_table() {
  using T = ParamType;
  using P = OutputSpec;
  static const ParamTable<P> table{
      "output",
      "where the outputs go: the folder, HDF5 on or off, PNGs, compression, the fields to write",
      {{"dir", T::text, BLEEDSIM_MEMBER(P, dir), "", {},
        "the output folder, relative to the working directory; --out overrides", "\"out/<name>\""},
       {"hdf5", T::flag, BLEEDSIM_MEMBER(P, hdf5), "", {}, "write frames.h5; --no-hdf5 overrides"},
       {"png_every", T::integer, BLEEDSIM_MEMBER(P, png_every), "", {0, 1000000},
        "PNGs of frame 0, every Nth frame and the last; 0: none; --png-every overrides"},
       {"contact_sheet", T::integer, BLEEDSIM_MEMBER(P, contact_sheet), "", {0, 64},
        "N frames from the first to the last in contact_sheet.png; 0: none; --contact-sheet overrides"},
       {"deflate", T::integer, BLEEDSIM_MEMBER(P, deflate_level), "", {0, 9}, "the HDF5 gzip level"},
       {"fields", T::names, BLEEDSIM_MEMBER(P, fields), "", {},
        "fields written besides the frame; [] writes all but the per-particle arrays, which are written "
        "only when listed"}},
      {},
      resolve_output};
  return table;
}

}  // namespace bleedsim

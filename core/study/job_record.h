#pragma once
// One job of an accuracy study, done: a setting run with one seed on one backend (docs/accuracy.md,
// "Jobs and records"). A record holds everything the analysis needs of its run, so that jobs run
// anywhere, in any order, and travel as bytes: a versioned little-endian format of its own,
// doubles and floats as their IEEE bytes. Its data (what the run computed) and its run (which job
// slot, where it ran and how long it took) are kept in separate sections: two runs of one setting
// and seed, on either backend, on any machine, give the same data bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "core/runtime/backend.h"

namespace bleedsim {

// "BSJOBREC" and the format's version: a change of the layout below is a new version.
constexpr char kJobRecordMagic[8] = {'B', 'S', 'J', 'O', 'B', 'R', 'E', 'C'};
constexpr std::uint32_t kJobRecordVersion = 2;  // 2: the fastest particle's speed, every frame

struct JobRecord {
  // What ran: the study it belongs to (Study::key()), the setting and the seed.
  std::uint64_t study_key = 0;
  std::uint32_t setting = 0, seed_index = 0;
  std::uint64_t seed = 0;    // the physics' seed it ran with
  std::string status = "ok";  // or "refused: <why>" (then nothing below but the timing's backend)
  // Every frame's measures (core/study/study_metrics.h; NaN in a scene without a film).
  std::vector<double> front_mm, covered_area_mm2, volume_mm3, pile_height_mm, fastest_mm_s;
  // The snapshot frames' fields on the common grid, one snapshot after another: film and stain one
  // value per cell (empty where the scene lacks them), colour three.
  std::int32_t grid_width = 0, grid_height = 0;
  std::vector<std::int32_t> snapshot_frames;
  std::vector<float> film_mm, stain, rgb;
  // The run, apart from the data: the job's index, where it ran and each frame's compute.
  std::uint32_t job = 0;
  BackendKind backend = BackendKind::cpu;
  std::string device;
  std::vector<double> frame_seconds;
};

std::vector<std::uint8_t> serialize(const JobRecord& record);
// Throws std::runtime_error naming what is wrong: not a record, another version, truncated.
JobRecord deserialize(const std::vector<std::uint8_t>& bytes);
// The data section's bytes: equal for two runs of one setting and seed (the backends are bit-exact).
std::vector<std::uint8_t> data_bytes(const JobRecord& record);

}  // namespace bleedsim

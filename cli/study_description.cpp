#include "cli/study_description.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <system_error>

#include "core/runtime/input_error.h"
#include "core/scaleout/byte_codec.h"
#include "core/study/study_knobs.h"

namespace bleedsim::cli {
namespace {

// A change of the layout below is a new version: a merge refuses shards of another.
constexpr std::uint32_t kStudyDescriptionVersion = 2;

}  // namespace

// Each level the whole of its place between the commas, a decimal number as std::from_chars reads it
// (strtod would take "0x10" and " 10").
KnobLevels parse_knob(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const Knob* knob = find_knob(name);
  if (!knob) throw InputError({}, "--knob", unknown_knob_message(name));
  if (equals == std::string::npos || equals + 1 == text.size())
    throw InputError({}, "--knob", "write it as " + name + "=v1,v2,... (got '" + text + "')");
  const std::string list = text.substr(equals + 1), key = "--knob " + name;
  KnobLevels levels{knob, {}};
  for (std::size_t at = 0; at <= list.size();) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string level = "level " + std::to_string(levels.levels.size() + 1);
    const std::string value = list.substr(at, comma - at);
    if (value.empty()) throw InputError({}, key, level + " of '" + list + "' is empty: write numbers between the commas");
    double v = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (error == std::errc::invalid_argument || end != value.data() + value.size())
      throw InputError({}, key, level + ", '" + value + "', is not a decimal number");
    if (error == std::errc::result_out_of_range) throw InputError({}, key, level + ", '" + value + "', is out of a double's range");
    levels.levels.push_back(v);
    at = comma + 1;
  }
  return levels;
}

std::vector<std::uint8_t> describe_study(const Scenario& scenario, const std::vector<std::string>& knobs,
                                         const StudySpec& spec) {
  ByteWriter out;
  out.u32(kStudyDescriptionVersion);
  out.text(std::filesystem::absolute(scenario.path).lexically_normal().string());
  out.text(scenario.text);
  out.u32(std::uint32_t(knobs.size()));
  for (const std::string& knob : knobs) out.text(knob);
  out.u32(std::uint32_t(spec.backends.size()));
  for (const BackendKind backend : spec.backends) out.u32(std::uint32_t(backend));
  out.u32(spec.duration_s ? 1u : 0u);
  out.f64(spec.duration_s.value_or(0.0));
  out.i32(spec.seeds);
  out.i32(spec.cpu_threads);
  return out.take();
}

DescribedStudy read_study_description(const std::vector<std::uint8_t>& bytes, const std::string& shard) {
  ByteReader in(bytes.data(), bytes.size());
  DescribedStudy d;
  try {
    if (in.u32("the description's version") != kStudyDescriptionVersion)
      throw InputError({}, shard, "written by another version of bleedsim study (its description's format differs)");
    d.scenario_path = in.text("the scenario's path");
    d.scenario_text = in.text("the scenario's text");
    for (std::uint32_t k = in.u32("the knob count"); k > 0; --k) d.spec.knobs.push_back(parse_knob(in.text("a knob")));
    for (std::uint32_t b = in.u32("the backend count"); b > 0; --b) d.spec.backends.push_back(BackendKind(in.u32("a backend")));
    const bool timed = in.u32("the duration's flag") != 0;
    const double duration_s = in.f64("the duration");
    if (timed) d.spec.duration_s = duration_s;
    d.spec.seeds = in.i32("the seeds");
    d.spec.cpu_threads = in.i32("the threads");
  } catch (const TruncatedBytes& e) {
    throw InputError({}, shard, std::string("its study description is cut off: ") + e.what());
  }
  return d;
}

}  // namespace bleedsim::cli

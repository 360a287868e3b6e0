#pragma once
// Parameter tables (docs/architecture.md, "Parameters"). Each parameter struct has one table
// beside it: per key its type, unit, default, bounds and one line of documentation, and the rules
// between keys. Whatever reads, checks or documents parameters reads the table — the scenario
// reader (core/io), the check of scenes built in code (Simulation), the study's knobs,
// `bleedsim params` and the generated tables of docs/scenario-format.md — so no rule and no
// default is written twice. Defaults are the struct's own: a table shows what `P{}` holds.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace bleedsim {

struct Scene;

enum class ParamType { integer, number, vector, vector3, text, flag, names };
const char* to_string(ParamType type);

// Why a value cannot be used, and the key to blame ("particles.substeps"); empty when it can.
struct ParamProblem {
  std::string key;
  std::string message;
  explicit operator bool() const { return !key.empty(); }
  std::string text() const { return key + ": " + message; }
};

// The values a number allows: low … high (low itself excluded when `above`: sizes must be > 0),
// and, when `only` is given, one of those.
struct Range {
  Range() = default;
  Range(double low_end, double high_end, bool low_excluded = false, std::vector<double> one_of = {})
      : low(low_end), high(high_end), above(low_excluded), only(std::move(one_of)) {}

  double low = 0;
  double high = 0;
  bool above = false;
  std::vector<double> only;

  bool contains(double v) const;
  // "greater than 0 and at most 100", "between 0 and 1e+06", "1, 2 or 4"; integers as integers.
  std::string describe(ParamType type) const;
};

// A parameter of two or three components ([x, y] or [x, y, z] in a file) held in as many members.
struct VectorRef {
  double& x;
  double& y;
  double* z = nullptr;  // a three-component one's third
};

// Where a parameter lives in its struct: a function from the struct to the member. A key that no
// member holds (a file's way of saying something else, such as particles.volume_mm3_per_s) has
// none; the table's resolve() reads it from what the file wrote.
template <class P>
using ParamField =
    std::variant<std::monostate, int& (*)(P&), std::uint8_t& (*)(P&), std::uint64_t& (*)(P&), double& (*)(P&),
                 VectorRef (*)(P&), std::string& (*)(P&), bool& (*)(P&), std::vector<std::string>& (*)(P&)>;

// The member `path` of P as a ParamField: BLEEDSIM_MEMBER(ParticleParams, diameter_mm).
#define BLEEDSIM_MEMBER(P, path) (+[](P& p) -> decltype(auto) { return (p.path); })
#define BLEEDSIM_VECTOR(P, x, y) (+[](P& p) { return VectorRef{p.x, p.y}; })
#define BLEEDSIM_VECTOR3(P, x, y, z) (+[](P& p) { return VectorRef{p.x, p.y, &p.z}; })

template <class P>
struct Param {
  const char* key;  // within its table: "diameter_mm"
  ParamType type;
  ParamField<P> field;
  const char* unit;  // "" when it has none
  Range range;       // numbers, integers and each component of a vector
  const char* doc;   // one line: what it does
  const char* default_note = nullptr;  // the default in words, where it is not P{}'s value
  bool required = false;               // a file must give it
  const char* allowed_note = nullptr;  // the allowed values in words, where a rule, not the range, says
};

// What a scenario file wrote in one table: its keys, and the values of keys no member holds.
struct Written {
  std::string file;                           // the scenario file (defaults drawn from its name)
  std::set<std::string> keys;                 // "fade_s", ...
  std::map<std::string, double> numbers;      // keys without a member: their values
  std::map<std::string, std::string> texts;
  bool has(const std::string& key) const { return keys.count(key) != 0; }
};

template <class P>
struct ParamTable {
  const char* name;  // the scenario's table: "particles" ([particles]); "cut" for [[cut]]
  const char* doc;   // what its presence declares
  std::vector<Param<P>> params;
  // Rules between keys, or against the scene (the panel, the frame rate); checked for files and
  // for scenes built in code alike. A rule's problem names the key within the table ("substeps").
  struct Rule {
    const char* doc;
    ParamProblem (*check)(const P& params, const Scene& scene);
  };
  std::vector<Rule> rules;
  // What a file leaves out or says another way: defaults that depend on other keys, and keys no
  // member holds. Files only: a scene built in code sets every member itself. Its problem, too,
  // names the key within the table.
  ParamProblem (*resolve)(P& params, const Written& written, const Scene& scene) = nullptr;
};

// "particles.diameter_mm".
template <class P>
std::string full_key(const ParamTable<P>& table, const Param<P>& param) {
  return std::string(table.name) + "." + param.key;
}

// The problem with one numeric value of a parameter of `type` (an integer's must be whole), or none.
ParamProblem range_problem(const std::string& key, ParamType type, const Range& range, double value);

// The first problem of `params` against its table: each member's range, then the rules. Keys are
// named under `prefix` ("cut[2]"), or under the table's name when it is empty.
template <class P>
ParamProblem check_params(const ParamTable<P>& table, const P& params, const Scene& scene,
                          const std::string& prefix = "");

// A parameter as people read it (docs, `bleedsim params`), whatever its struct.
struct ParamView {
  std::string key;
  ParamType type;
  std::string unit;
  Range range;
  std::string doc;
  bool required;
  std::string default_note;                  // empty: `default_value` says it
  std::string allowed_note;                  // empty: the range says it
  std::variant<std::monostate, double, std::vector<double>, std::string, bool,
               std::vector<std::string>>
      default_value;                         // P{}'s; monostate: none (required, or no member holds it)
  std::string default_text() const;          // "0.2", "[0, 1000]", "true", "the diameter", "**required**"
  std::string allowed_text() const;          // "greater than 0, at most 100"
};

struct TableView {
  std::string name;
  std::string doc;
  std::vector<ParamView> params;
  std::vector<std::string> rules;
};

template <class P>
TableView describe(const ParamTable<P>& table);

}  // namespace bleedsim

#include "core/runtime/params_impl.h"

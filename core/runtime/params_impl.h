#pragma once
// The templates of core/runtime/params.h: checking and describing a table of any struct.
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace bleedsim {
namespace params_detail {

// The member a field names. Tables only read through it here: the const is taken off because the
// same function serves the reader, which writes.
template <class P, class T>
T& member(T& (*field)(P&), const P& params) {
  return field(const_cast<P&>(params));
}

template <class P, class T>
double as_number(T& (*field)(P&), const P& params) {
  return static_cast<double>(member(field, params));
}

}  // namespace params_detail

template <class P>
ParamProblem check_params(const ParamTable<P>& table, const P& params, const Scene& scene, const std::string& prefix) {
  const std::string at = prefix.empty() ? std::string(table.name) : prefix;
  for (const Param<P>& param : table.params) {
    const std::string key = at + "." + param.key;
    ParamProblem problem;
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          if constexpr (std::is_same_v<F, VectorRef (*)(P&)>) {
            const VectorRef v = field(const_cast<P&>(params));
            problem = range_problem(key + ".x", param.type, param.range, v.x);
            if (!problem) problem = range_problem(key + ".y", param.type, param.range, v.y);
            if (!problem && v.z) problem = range_problem(key + ".z", param.type, param.range, *v.z);
          } else if constexpr (std::is_same_v<F, int& (*)(P&)> || std::is_same_v<F, std::uint8_t& (*)(P&)> ||
                               std::is_same_v<F, std::uint64_t& (*)(P&)> || std::is_same_v<F, double& (*)(P&)>) {
            problem = range_problem(key, param.type, param.range, params_detail::as_number(field, params));
          }
        },
        param.field);
    if (problem) return problem;
  }
  for (const auto& rule : table.rules)
    if (ParamProblem problem = rule.check(params, scene)) return {at + "." + problem.key, problem.message};
  return {};
}

template <class P>
TableView describe(const ParamTable<P>& table) {
  const P defaults{};
  TableView view{table.name, table.doc, {}, {}};
  for (const Param<P>& param : table.params) {
    ParamView p{param.key, param.type, param.unit, param.range, param.doc, param.required,
                param.default_note ? param.default_note : "", param.allowed_note ? param.allowed_note : "", {}};
    if (!param.required) {
      std::visit(
          [&](auto field) {
            using F = decltype(field);
            if constexpr (std::is_same_v<F, std::monostate>) {
            } else if constexpr (std::is_same_v<F, VectorRef (*)(P&)>) {
              const VectorRef v = field(const_cast<P&>(defaults));
              p.default_value = v.z ? std::vector<double>{v.x, v.y, *v.z} : std::vector<double>{v.x, v.y};
            } else if constexpr (std::is_same_v<F, std::string& (*)(P&)> || std::is_same_v<F, bool& (*)(P&)> ||
                                 std::is_same_v<F, std::vector<std::string>& (*)(P&)>) {
              p.default_value = params_detail::member(field, defaults);
            } else {
              p.default_value = params_detail::as_number(field, defaults);
            }
          },
          param.field);
    }
    view.params.push_back(std::move(p));
  }
  for (const auto& rule : table.rules) view.rules.push_back(rule.doc);
  return view;
}

}  // namespace bleedsim

namespace bleedsim {

// The parameter `key` of a table (std::out_of_range when it has none): for code that shares one
// parameter's range or documentation, such as a cut's defaults or a study's knob.
template <class P>
const Param<P>& param_named(const ParamTable<P>& table, const std::string& key) {
  for (const Param<P>& param : table.params)
    if (key == param.key) return param;
  throw std::out_of_range(std::string("no parameter '") + key + "' in [" + table.name + "]");
}

}  // namespace bleedsim

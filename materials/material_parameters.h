#pragma once
// A material's parameters, declared once in the material's own file (its static
// `parameters()`): name, type, accepted range, default and one line of documentation. The
// range check below, the scene reader and writer (core/scene_file/material_json.*) and the scene
// format's table in docs/scene-format.md are all driven from that declaration, so adding a
// material or a parameter touches the material's file alone.
//
// Three kinds of parameter cover the book's materials: a colour (three numbers, each in a
// range), a number (in a range, optionally with a default) and a choice (one of a few named
// values of an enum, with a default).

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>

#include "core/geometry/vec3.h"

namespace rtiow {

// A material parameter out of range: which one, which component (-1 for a number), its value
// and the rule it breaks. Scenes built in C++ and scene files are refused in the same words.
struct ParameterProblem {
  std::string field;
  int component = -1;
  double value = 0.0;
  std::string rule;  // "must be ..."
};

// A number as the rules print it (%g: 0.001, 1e+06).
inline std::string parameter_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

// Three numbers, each in [min, max]. Always required: a colour has no neutral default.
template <typename M>
struct ColorParameter {
  const char* name;
  Color M::*member;
  float min, max;
  std::string_view doc;

  std::string rule() const {
    return "must be in [" + parameter_number(min) + ", " + parameter_number(max) + "]";
  }
  std::optional<ParameterProblem> check(const M& m) const {
    const Color& c = m.*member;
    for (int i = 0; i < 3; ++i) {
      const float v = c[std::size_t(i)];
      if (!(v >= min && v <= max)) return ParameterProblem{name, i, v, rule()};
    }
    return std::nullopt;
  }
};

// One number in [min, max]; `fallback` when a file leaves it out (none: required). With
// `clamps_above`, a scene file's value above max acts as max (the book clamps metal's fuzz),
// while a material built in C++ with such a value is refused.
template <typename M>
struct NumberParameter {
  const char* name;
  float M::*member;
  std::optional<float> fallback;
  float min, max;
  bool clamps_above;
  std::string_view doc;

  std::string rule() const {
    if (clamps_above) {
      return "must be >= " + parameter_number(min) + " (values above " + parameter_number(max) +
             " act as " + parameter_number(max) + ")";
    }
    return "must be from " + parameter_number(min) + " to " + parameter_number(max);
  }
  std::optional<ParameterProblem> check(const M& m) const {
    const float v = m.*member;
    if (!(v >= min)) return ParameterProblem{name, -1, v, rule()};
    if (!(v <= max)) {
      return ParameterProblem{name, -1, v,
                              clamps_above ? "must be at most " + parameter_number(max) +
                                                 " (a scene file's larger value acts as " +
                                                 parameter_number(max) + ")"
                                           : rule()};
    }
    return std::nullopt;
  }
  // What a file's value becomes.
  float from_file(float v) const { return clamps_above && v > max ? max : v; }
};

// One of `choices`, named by `to_string(choice)`; `fallback` when a file leaves it out.
template <typename M, typename E, std::size_t N>
struct ChoiceParameter {
  const char* name;
  E M::*member;
  E fallback;
  std::array<E, N> choices;
  std::string_view doc;

  // "\"schlick\" or \"exact\"": how an error and the docs name the choices.
  std::string choice_list(const char* quote = "\"") const {
    std::string list;
    for (std::size_t i = 0; i < N; ++i) {
      if (i) list += i + 1 == N ? " or " : ", ";
      list.append(quote).append(to_string(choices[i])).append(quote);
    }
    return list;
  }
  std::optional<E> parse(std::string_view text) const {
    for (const E e : choices) {
      if (text == to_string(e)) return e;
    }
    return std::nullopt;
  }
  std::optional<ParameterProblem> check(const M& m) const {
    for (const E e : choices) {
      if (m.*member == e) return std::nullopt;
    }
    return ParameterProblem{name, -1, double(int(m.*member)), "must be " + choice_list()};
  }
};

// Calls f(declaration) for each of M's parameters, in declaration order.
template <typename M, typename F>
constexpr void for_each_parameter(F&& f) {
  std::apply([&](const auto&... p) { (f(p), ...); }, M::parameters());
}

// The first parameter of `m` outside its declared range, if any.
template <typename M>
requires requires {
  M::parameters();
}
std::optional<ParameterProblem> check_parameters(const M& m) {
  std::optional<ParameterProblem> problem;
  for_each_parameter<M>([&](const auto& p) {
    if (!problem) problem = p.check(m);
  });
  return problem;
}

}  // namespace rtiow

#include "core/scene_file/material_json.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/io/json_writer.h"
#include "core/scene_file/json_float.h"

namespace rtiow {
namespace {

using scene_json::Place;
using scene_json::Reader;

template <typename M>
void read_parameter(const Reader& r, const JsonValue& v, const Place& p, const ColorParameter<M>& d,
                    M& m) {
  m.*d.member = r.numbers3(r.require(v, p, d.name), Place(p, d.name));
}

template <typename M>
void read_parameter(const Reader& r, const JsonValue& v, const Place& p,
                    const NumberParameter<M>& d, M& m) {
  const JsonValue* value = d.fallback ? r.find(v, d.name) : &r.require(v, p, d.name);
  m.*d.member = value ? d.from_file(r.single(*value, Place(p, d.name))) : *d.fallback;
}

template <typename M, typename E, std::size_t N>
void read_parameter(const Reader& r, const JsonValue& v, const Place& p,
                    const ChoiceParameter<M, E, N>& d, M& m) {
  m.*d.member = d.fallback;
  const JsonValue* value = r.find(v, d.name);
  if (!value) return;
  const Place at(p, d.name);
  const std::string expected = d.choice_list();
  const std::string_view text = r.string(*value, at, expected.c_str());
  const std::optional<E> choice = d.parse(text);
  if (!choice) r.fail(at, "must be " + expected + ", got " + quote_value(text, 40));
  m.*d.member = *choice;
}

// The fields a material of type M may have: "type" and its parameters.
template <typename M>
std::vector<std::string_view> fields_of() {
  std::vector<std::string_view> fields{"type"};
  for_each_parameter<M>([&](const auto& d) { fields.push_back(d.name); });
  return fields;
}

template <typename M>
M read_fields(const Reader& r, const JsonValue& v, const Place& p) {
  r.only(v, p, fields_of<M>());
  M m{};
  for_each_parameter<M>([&](const auto& d) { read_parameter(r, v, p, d, m); });
  return m;
}

// The same rules over a member's flat fields (material_from_fields).
template <typename M>
bool take_parameter(const MemberFields& fields, const ColorParameter<M>& d, M& m) {
  const MemberField* field = fields.find(d.name);
  if (!field || field->kind != MemberField::kTriple) return false;
  m.*d.member = Color(Vec3d{field->numbers[0], field->numbers[1], field->numbers[2]});
  return true;
}

template <typename M>
bool take_parameter(const MemberFields& fields, const NumberParameter<M>& d, M& m) {
  const MemberField* field = fields.find(d.name);
  if (!field) {
    if (d.fallback) m.*d.member = *d.fallback;
    return d.fallback.has_value();
  }
  const double value = field->numbers[0];
  if (field->kind != MemberField::kNumber ||
      std::abs(value) > double(std::numeric_limits<float>::max())) {
    return false;
  }
  m.*d.member = d.from_file(float(value));
  return true;
}

template <typename M, typename E, std::size_t N>
bool take_parameter(const MemberFields& fields, const ChoiceParameter<M, E, N>& d, M& m) {
  m.*d.member = d.fallback;
  const MemberField* field = fields.find(d.name);
  if (!field) return true;
  if (field->kind != MemberField::kString) return false;
  const std::optional<E> choice = d.parse(field->text);
  if (choice) m.*d.member = *choice;
  return choice.has_value();
}

template <typename M>
std::optional<Material> take_fields(const MemberFields& fields) {
  M m{};
  bool taken = true;
  std::size_t present = 1;  // "type"
  for_each_parameter<M>([&](const auto& d) {
    taken = taken && take_parameter(fields, d, m);
    present += fields.find(d.name) != nullptr;
  });
  if (!taken || present != fields.size()) return std::nullopt;  // a field M does not have
  return Material(m);
}

// Parameters as JSON text, built directly: a million materials are written for a scene's
// digest.
template <typename M>
std::string value_text(const ColorParameter<M>& d, const M& m) {
  const Color& c = m.*d.member;
  std::string text = "[";
  append_json_float(text, c.x);
  text.push_back(',');
  append_json_float(text, c.y);
  text.push_back(',');
  append_json_float(text, c.z);
  text.push_back(']');
  return text;
}
template <typename M>
std::string value_text(const NumberParameter<M>& d, const M& m) {
  return json_float_text(m.*d.member);
}
template <typename M, typename E, std::size_t N>
std::string value_text(const ChoiceParameter<M, E, N>& d, const M& m) {
  return json_quoted(to_string(m.*d.member));
}

template <typename M>
bool is_default(const ColorParameter<M>&, const M&) {
  return false;  // required
}
template <typename M>
bool is_default(const NumberParameter<M>& d, const M& m) {
  return d.fallback && m.*d.member == *d.fallback;
}
template <typename M, typename E, std::size_t N>
bool is_default(const ChoiceParameter<M, E, N>& d, const M& m) {
  return m.*d.member == d.fallback;
}

// The docs' columns for each kind of parameter: its value, its default.
template <typename M>
std::string value_doc(const ColorParameter<M>& d) {
  return "3 numbers, each in [" + parameter_number(d.min) + ", " + parameter_number(d.max) + "]";
}
template <typename M>
std::string value_doc(const NumberParameter<M>& d) {
  if (d.clamps_above) {
    return "a number >= " + parameter_number(d.min) + " (above " + parameter_number(d.max) +
           " acts as " + parameter_number(d.max) + ")";
  }
  return "a number from " + parameter_number(d.min) + " to " + parameter_number(d.max);
}
template <typename M, typename E, std::size_t N>
std::string value_doc(const ChoiceParameter<M, E, N>& d) {
  return d.choice_list("`");
}
template <typename M>
std::string default_doc(const ColorParameter<M>&) {
  return "required";
}
template <typename M>
std::string default_doc(const NumberParameter<M>& d) {
  return d.fallback ? parameter_number(*d.fallback) : "required";
}
template <typename M, typename E, std::size_t N>
std::string default_doc(const ChoiceParameter<M, E, N>& d) {
  return "`" + std::string(to_string(d.fallback)) + "`";
}

}  // namespace

Material read_material(const Reader& r, const JsonValue& v, const Place& p) {
  r.object(v, p);
  const std::string_view type = r.string(r.require(v, p, "type"), Place(p, "type"), "a string");
  std::optional<Material> material;
  for_each_material_type([&](const auto& kind) {
    using M = std::decay_t<decltype(kind)>;
    if (!material && type == M::kType) material = read_fields<M>(r, v, p);
  });
  if (!material) {
    r.fail(Place(p, "type"), "unknown material type " + quote_value(type, 40) + " (expected " +
                                 material_type_names() + ")");
  }
  // The ranges are the material's own rule, the same for a scene built in C++.
  if (const auto problem = check_parameters(*material)) {
    const Place field(p, problem->field);
    const std::string what = problem->rule + ", got " + Reader::format(problem->value);
    if (problem->component >= 0) r.fail(Place(field, std::size_t(problem->component)), what);
    r.fail(field, what);
  }
  return *material;
}

std::optional<Material> material_from_fields(const MemberFields& fields) {
  const MemberField* type = fields.find("type");
  if (!type || type->kind != MemberField::kString) return std::nullopt;
  std::optional<Material> material;
  for_each_material_type([&](const auto& kind) {
    using M = std::decay_t<decltype(kind)>;
    if (type->text == M::kType) material = take_fields<M>(fields);
  });
  if (material && check_parameters(*material)) return std::nullopt;
  return material;
}

std::string material_to_json(const Material& material) {
  return visit_material(material, [](const auto& m) {
    using M = std::decay_t<decltype(m)>;
    std::string text = "{\"type\":" + json_quoted(M::kType);
    for_each_parameter<M>([&](const auto& d) {
      if (!is_default(d, m))
        text.append(",\"").append(d.name).append("\":").append(value_text(d, m));
    });
    return text.append("}");
  });
}

std::string material_format_table() {
  std::string table =
      "| `type` | parameter | value | default | meaning |\n"
      "|---|---|---|---|---|\n";
  for_each_material_type([&](const auto& kind) {
    using M = std::decay_t<decltype(kind)>;
    bool first = true;
    for_each_parameter<M>([&](const auto& d) {
      table.append("| ")
          .append(first ? "`" + std::string(M::kType) + "`: " + M::kDoc : std::string())
          .append(" | `")
          .append(d.name)
          .append("` | ")
          .append(value_doc(d))
          .append(" | ")
          .append(default_doc(d))
          .append(" | ")
          .append(d.doc)
          .append(" |\n");
      first = false;
    });
  });
  return table;
}

}  // namespace rtiow

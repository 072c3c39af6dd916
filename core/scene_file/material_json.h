#pragma once
// Materials in a scene file, driven by each material's declaration of its parameters
// (materials/material_parameters.h): reading one with the errors a user sees, writing one,
// and the scene format's table of materials in docs/scene-format.md. Internal to the scene
// reader and writer (it needs RapidJSON).

#include <optional>
#include <string>

#include "core/scene_file/json_reader.h"
#include "core/scene_file/member_fields.h"
#include "materials/material.h"

namespace rtiow {

// The material at `p` (an object with "type" and its parameters); throws InvalidInput naming
// the place of the first problem.
Material read_material(const scene_json::Reader& r, const JsonValue& v, const scene_json::Place& p);

// The material `fields` give, or nothing where read_material would refuse them: the fast
// reading of a big file, which builds no JSON values (what it refuses is read again in one
// piece, for the message).
std::optional<Material> material_from_fields(const MemberFields& fields);

// One material as a JSON object on one line: its type, then each parameter in declaration
// order, leaving out those equal to their default.
std::string material_to_json(const Material& material);

// The scene format's table of materials and their parameters, in Markdown.
std::string material_format_table();

}  // namespace rtiow

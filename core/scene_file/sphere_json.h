#pragma once
// A sphere in a scene file: {"center": [x, y, z], "radius": r, "material": "name"}, read with
// the errors a user sees, or from a member's flat fields by the fast reading of a big file.
// Internal to the scene reader (it needs RapidJSON).

#include <optional>
#include <string_view>

#include "core/geometry/vec3.h"
#include "core/scene_file/json_reader.h"
#include "core/scene_file/member_fields.h"

namespace rtiow {

// A sphere as read, its material still a name: a view into the text it was read from (a JSON
// value's, or a window's), which the caller keeps until the name is resolved.
struct SphereRecord {
  Vec3 center;
  float radius = 0.0f;
  std::string_view material;
};

// The sphere at `p`; throws InvalidInput naming the place of the first problem.
SphereRecord read_sphere(const scene_json::Reader& r, const JsonValue& v,
                         const scene_json::Place& p);

// The sphere `fields` give, or nothing where read_sphere would refuse them.
std::optional<SphereRecord> sphere_from_fields(const MemberFields& fields);

}  // namespace rtiow

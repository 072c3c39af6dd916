#include "core/scene_file/sphere_json.h"

#include <cmath>

#include "core/limits/input_limits.h"

namespace rtiow {

using scene_json::Place;
using scene_json::Reader;

SphereRecord read_sphere(const Reader& r, const JsonValue& s, const Place& p) {
  r.object(s, p);
  r.only(s, p, {"center", "radius", "material"});
  const Vec3 center(r.vec3(r.require(s, p, "center"), Place(p, "center")));
  const Place radius_at(p, "radius");
  const auto radius = float(r.bounded(r.require(s, p, "radius"), radius_at));
  if (radius == 0.0f) r.fail(radius_at, "must not be 0 (negative makes a hollow sphere)");
  if (std::abs(radius) < limits::kMinRadius) {
    r.fail(radius_at, "must be at least 1.2e-38 in size (float's smallest normal)");
  }
  const std::string_view material =
      r.string(r.require(s, p, "material"), Place(p, "material"), "a material name");
  return {center, radius, material};
}

std::optional<SphereRecord> sphere_from_fields(const MemberFields& fields) {
  // Reader::bounded's rule: within the range rtiow traces.
  const auto bounded = [](double d) { return std::abs(d) <= limits::kMaxCoordinate; };
  const MemberField* center = fields.find("center");
  const MemberField* radius = fields.find("radius");
  const MemberField* material = fields.find("material");
  if (fields.size() != 3 || !center || !radius || !material ||
      center->kind != MemberField::kTriple || radius->kind != MemberField::kNumber ||
      material->kind != MemberField::kString) {
    return std::nullopt;
  }
  const std::array<double, 3>& c = center->numbers;
  if (!bounded(c[0]) || !bounded(c[1]) || !bounded(c[2]) || !bounded(radius->numbers[0])) {
    return std::nullopt;
  }
  const auto r = float(radius->numbers[0]);
  if (std::abs(r) < limits::kMinRadius) return std::nullopt;
  return SphereRecord{Vec3(Vec3d{c[0], c[1], c[2]}), r, material->text};
}

}  // namespace rtiow

#include "core/scene_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "core/input_file.h"
#include "core/input_limits.h"
#include "core/json_stream.h"

namespace rtiow {
namespace {

using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

constexpr int kVersion = 1;

// A key as a JSON-pointer token, cut so that an error line stays short.
std::string escape_pointer_token(const std::string& key) {
  constexpr std::size_t kMaxShown = 40;
  std::string out;
  for (char c : key.substr(0, kMaxShown)) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  if (key.size() > kMaxShown) out += "...";
  return one_line(out, 4 * kMaxShown);  // NUL and control characters escaped
}

// Reading: every accessor knows where it is (a JSON pointer) and says so when it refuses.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw InvalidInput(source_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + what);
  }

  const json& object(const json& v, const std::string& pointer) const {
    if (!v.is_object()) fail(pointer, "must be an object, got " + describe(v));
    return v;
  }

  // Refuses keys outside `allowed`: a misspelt field must not be ignored silently.
  void only(const json& obj, const std::string& pointer,
            std::initializer_list<const char*> allowed) const {
    for (const auto& item : obj.items()) {
      bool known = false;
      for (const char* a : allowed) known = known || item.key() == a;
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(pointer + "/" + escape_pointer_token(item.key()),
             "unknown field (expected one of: " + list + ")");
      }
    }
  }

  const json* find(const json& obj, const char* key) const {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  const json& require(const json& obj, const std::string& pointer, const char* key) const {
    const json* v = find(obj, key);
    if (!v) fail(pointer, std::string("missing field \"") + key + "\"");
    return *v;
  }

  double number(const json& v, const std::string& pointer) const {
    if (!v.is_number()) fail(pointer, "must be a number, got " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(pointer, "must be finite");
    return d;
  }

  // A float-valued field: finite also after rounding to float.
  float single(const json& v, const std::string& pointer) const {
    const double d = number(v, pointer);
    if (std::abs(d) > double(std::numeric_limits<float>::max())) {
      fail(pointer, "is too large for single precision");
    }
    return float(d);
  }

  int integer(const json& v, const std::string& pointer, int lo, int hi) const {
    if (!v.is_number_integer()) fail(pointer, "must be a whole number, got " + describe(v));
    // An unsigned value beyond int64 would wrap to a negative one: compare it unconverted.
    const bool in_range = v.is_number_unsigned()
                              ? v.get<std::uint64_t>() <= std::uint64_t(std::max(hi, 0)) &&
                                    std::int64_t(v.get<std::uint64_t>()) >= lo
                              : v.get<std::int64_t>() >= lo && v.get<std::int64_t>() <= hi;
    if (!in_range) {
      fail(pointer, "must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                        describe(v));
    }
    return int(v.get<std::int64_t>());
  }

  // A coordinate or length: within the range float rays and Embree trace.
  double bounded(const json& v, const std::string& pointer) const {
    const double d = number(v, pointer);
    if (std::abs(d) > limits::kMaxCoordinate) {
      fail(pointer, "is beyond the limit of +-" + format(limits::kMaxCoordinate) +
                        " (the range rtiow traces), got " + format(d));
    }
    return d;
  }

  Vec3 vec3f(const json& v, const std::string& pointer) const {
    const Vec3d d = vec3(v, pointer);
    return Vec3(d);
  }

  // A position or direction: three bounded numbers.
  Vec3d vec3(const json& v, const std::string& pointer) const {
    if (!v.is_array() || v.size() != 3) fail(pointer, "must be an array of 3 numbers");
    return {bounded(v[0], pointer + "/0"), bounded(v[1], pointer + "/1"),
            bounded(v[2], pointer + "/2")};
  }

  Color color(const json& v, const std::string& pointer) const {
    if (!v.is_array() || v.size() != 3) fail(pointer, "must be an array of 3 numbers");
    const Vec3d c{number(v[0], pointer + "/0"), number(v[1], pointer + "/1"),
                  number(v[2], pointer + "/2")};
    for (int i = 0; i < 3; ++i) {
      if (c[std::size_t(i)] < 0.0 || c[std::size_t(i)] > 1.0) {
        fail(pointer + "/" + std::to_string(i),
             "must be in [0, 1], got " + format(c[std::size_t(i)]));
      }
    }
    return Color(c);
  }

  static std::string format(double d) {
    std::ostringstream s;
    s << d;
    return s.str();
  }

  // A short, safe description of a value: never the dump of a whole container.
  static std::string describe(const json& v) {
    if (v.is_object()) return "an object of " + std::to_string(v.size()) + " members";
    if (v.is_array()) return "an array of " + std::to_string(v.size()) + " values";
    if (v.is_string()) return "string " + quote_value(v.get_ref<const std::string&>(), 40);
    return std::string(v.type_name()) + " " + v.dump();
  }

 private:
  std::string source_;
};

void read_camera(const Reader& r, const json& v, CameraSettings& cam) {
  const std::string p = "/camera";
  r.object(v, p);
  r.only(v, p,
         {"lookfrom", "lookat", "vup", "vfov", "aperture", "defocus_angle", "focus_distance"});
  cam.lookfrom = r.vec3(r.require(v, p, "lookfrom"), p + "/lookfrom");
  cam.lookat = r.vec3(r.require(v, p, "lookat"), p + "/lookat");
  cam.vup = Vec3d{0, 1, 0};
  if (const json* vup = r.find(v, "vup")) cam.vup = r.vec3(*vup, p + "/vup");
  cam.vfov_degrees = r.number(r.require(v, p, "vfov"), p + "/vfov");
  cam.focus_distance = length(cam.lookat - cam.lookfrom);
  if (const json* f = r.find(v, "focus_distance")) {
    cam.focus_distance = r.bounded(*f, p + "/focus_distance");
  }
  const json* aperture = r.find(v, "aperture");
  const json* angle = r.find(v, "defocus_angle");
  if (aperture && angle) r.fail(p, "give either \"aperture\" or \"defocus_angle\", not both");
  cam.aperture = 0.0;
  if (aperture) cam.aperture = r.bounded(*aperture, p + "/aperture");
  if (angle) {
    // The book's later editions: the lens subtends this angle (degrees) from the focus plane.
    const double degrees = r.number(*angle, p + "/defocus_angle");
    if (degrees < 0.0 || degrees >= 180.0) {
      r.fail(p + "/defocus_angle", "must be in [0, 180), got " + Reader::format(degrees));
    }
    cam.aperture = 2.0 * cam.focus_distance * std::tan(degrees * std::numbers::pi / 360.0);
  }
  try {
    validate(cam);
  } catch (const InvalidInput& e) {
    std::string what = e.what();
    if (what.rfind("camera: ", 0) == 0) what = what.substr(8);
    r.fail(p, what);
  }
}

void read_image(const Reader& r, const json& v, ImageSettings& image) {
  const std::string p = "/image";
  r.object(v, p);
  r.only(v, p, {"width", "height", "aspect_ratio", "spp", "depth"});
  image.width = r.integer(r.require(v, p, "width"), p + "/width", 1, limits::kMaxImageSide);
  const json* height = r.find(v, "height");
  const json* aspect = r.find(v, "aspect_ratio");
  if (height && aspect) r.fail(p, "give either \"height\" or \"aspect_ratio\", not both");
  if (!height && !aspect) r.fail(p, "missing field \"height\" (or \"aspect_ratio\")");
  if (height) {
    const int h = r.integer(*height, p + "/height", 1, limits::kMaxImageSide);
    image.aspect_ratio = double(image.width) / double(h);
  } else {
    image.aspect_ratio = r.number(*aspect, p + "/aspect_ratio");
    if (image.aspect_ratio <= 0.0) r.fail(p + "/aspect_ratio", "must be > 0");
    // The height it implies must be a size rtiow renders: checked here, never clamped.
    const double h = std::round(double(image.width) / image.aspect_ratio);
    if (!(h >= 1.0 && h <= double(limits::kMaxImageSide))) {
      r.fail(p + "/aspect_ratio", "gives a height of " + Reader::format(h) + " pixels for width " +
                                      std::to_string(image.width) + " (must be 1 to " +
                                      std::to_string(limits::kMaxImageSide) + ")");
    }
  }
  image.samples_per_pixel = 100;
  if (const json* spp = r.find(v, "spp")) {
    image.samples_per_pixel = r.integer(*spp, p + "/spp", 1, std::numeric_limits<int>::max());
  }
  image.max_depth = 50;
  if (const json* depth = r.find(v, "depth"))
    image.max_depth = r.integer(*depth, p + "/depth", 0, limits::kMaxDepth);
}

FresnelModel parse_fresnel(const std::string& name, const Reader& r, const std::string& p) {
  if (name == "schlick") return FresnelModel::Schlick;
  if (name == "exact") return FresnelModel::Exact;
  r.fail(p, "must be \"schlick\" or \"exact\", got \"" + name + "\"");
}

Material read_material(const Reader& r, const json& v, const std::string& p) {
  r.object(v, p);
  const json& type = r.require(v, p, "type");
  if (!type.is_string()) r.fail(p + "/type", "must be a string, got " + Reader::describe(type));
  const std::string kind = type.get<std::string>();
  if (kind == "lambertian") {
    r.only(v, p, {"type", "albedo"});
    return Lambertian{r.color(r.require(v, p, "albedo"), p + "/albedo")};
  }
  if (kind == "metal") {
    r.only(v, p, {"type", "albedo", "fuzz"});
    float fuzz = 0.0f;
    if (const json* f = r.find(v, "fuzz")) {
      fuzz = r.single(*f, p + "/fuzz");
      if (fuzz < 0.0f) r.fail(p + "/fuzz", "must be >= 0 (values above 1 act as 1)");
    }
    return make_metal(r.color(r.require(v, p, "albedo"), p + "/albedo"), fuzz);
  }
  if (kind == "dielectric") {
    r.only(v, p, {"type", "ior", "fresnel"});
    const double ior = r.number(r.require(v, p, "ior"), p + "/ior");
    if (!(ior >= limits::kMinIor && ior <= limits::kMaxIor)) {
      r.fail(p + "/ior", "must be from " + Reader::format(limits::kMinIor) + " to " +
                             Reader::format(limits::kMaxIor) + ", got " + Reader::format(ior));
    }
    Dielectric d{float(ior)};
    if (const json* f = r.find(v, "fresnel")) {
      if (!f->is_string()) r.fail(p + "/fresnel", "must be \"schlick\" or \"exact\"");
      d.fresnel = parse_fresnel(f->get<std::string>(), r, p + "/fresnel");
    }
    return d;
  }
  r.fail(p + "/type",
         "unknown material type \"" + kind + "\" (expected lambertian, metal or dielectric)");
}

// Material names to indices. Spheres may name a material before /materials defines it
// (keys have no order), so a name gets its index when first seen by either.
class MaterialTable {
 public:
  explicit MaterialTable(const Reader& r) : r_(r) {}

  void define(const std::string& name, const Material& m, const std::string& pointer) {
    Slot& slot = slots_[lookup(name)];
    if (slot.defined) r_.fail(pointer, "a second material of this name (duplicate key)");
    slot.defined = true;
    slot.material = m;
  }

  std::uint32_t refer(const std::string& name, std::size_t sphere) {
    const std::uint32_t index = lookup(name);
    if (!slots_[index].defined && slots_[index].first_user == kNoUser) {
      slots_[index].first_user = sphere;
      slots_[index].name = name;
    }
    return index;
  }

  // All materials, once every name a sphere used is defined.
  std::vector<Material> take() {
    std::vector<Material> materials;
    materials.reserve(slots_.size());
    for (const Slot& slot : slots_) {
      if (!slot.defined) {
        r_.fail("/spheres/" + std::to_string(slot.first_user) + "/material",
                "no material named " + quote_value(slot.name, 40) + " in /materials");
      }
      materials.push_back(slot.material);
    }
    return materials;
  }

 private:
  static constexpr std::size_t kNoUser = ~std::size_t(0);
  struct Slot {
    Material material{Lambertian{}};
    bool defined = false;
    std::size_t first_user = kNoUser;
    std::string name;  // kept only for an undefined name, for the error
  };

  std::uint32_t lookup(const std::string& name) {
    const auto [it, inserted] = index_.try_emplace(name, std::uint32_t(slots_.size()));
    if (inserted) {
      if (slots_.size() >= std::numeric_limits<std::uint32_t>::max()) {
        r_.fail("/materials", "more materials than rtiow indexes");
      }
      slots_.emplace_back();
    }
    return it->second;
  }

  const Reader& r_;
  std::unordered_map<std::string, std::uint32_t> index_;
  std::vector<Slot> slots_;
};

void read_sphere(const Reader& r, const json& s, std::size_t i, MaterialTable& table,
                 SphereSet& spheres) {
  const std::string p = "/spheres/" + std::to_string(i);
  r.object(s, p);
  r.only(s, p, {"center", "radius", "material"});
  const Vec3 center = r.vec3f(r.require(s, p, "center"), p + "/center");
  const auto radius = float(r.bounded(r.require(s, p, "radius"), p + "/radius"));
  if (radius == 0.0f) r.fail(p + "/radius", "must not be 0 (negative makes a hollow sphere)");
  const json& m = r.require(s, p, "material");
  if (!m.is_string())
    r.fail(p + "/material", "must be a material name, got " + Reader::describe(m));
  spheres.add(center, radius, table.refer(m.get_ref<const std::string&>(), i));
}

// Reads a scene from a stream: materials and spheres are converted as they are parsed and
// their text dropped; the rest (camera, image, background) is small and read at the end.
Scene read_scene(const Reader& r, CountingInput& input) {
  Scene scene;
  MaterialTable table(r);
  std::map<std::string, StreamedMember> streamed;
  streamed["materials"] = {true, [&](const std::string& key, std::size_t, const json& v) {
                             const std::string p = "/materials/" + escape_pointer_token(key);
                             table.define(key, read_material(r, v, p), p);
                           }};
  streamed["spheres"] = {false, [&](const std::string&, std::size_t i, const json& v) {
                           read_sphere(r, v, i, table, scene.spheres);
                         }};
  const json root = parse_json_stream(input, r.source(), streamed);

  r.object(root, "");
  r.only(
      root, "",
      {"version", "name", "scene_seed", "camera", "image", "background", "materials", "spheres"});
  r.integer(r.require(root, "", "version"), "/version", kVersion, kVersion);
  if (const json* name = r.find(root, "name")) {
    if (!name->is_string()) r.fail("/name", "must be a string, got " + Reader::describe(*name));
    scene.name = name->get<std::string>();
  }
  if (const json* seed = r.find(root, "scene_seed")) {
    if (!seed->is_number_unsigned()) r.fail("/scene_seed", "must be a whole number >= 0");
    scene.layout_seed = seed->get<std::uint64_t>();
  }
  read_camera(r, r.require(root, "", "camera"), scene.camera);
  read_image(r, r.require(root, "", "image"), scene.image);

  if (const json* bg = r.find(root, "background")) {
    r.object(*bg, "/background");
    r.only(*bg, "/background", {"horizon", "zenith"});
    scene.background.horizon =
        r.color(r.require(*bg, "/background", "horizon"), "/background/horizon");
    scene.background.zenith =
        r.color(r.require(*bg, "/background", "zenith"), "/background/zenith");
  }

  r.object(r.require(root, "", "materials"), "/materials");
  const json& spheres = r.require(root, "", "spheres");
  if (!spheres.is_array()) r.fail("/spheres", "must be an array, got " + Reader::describe(spheres));
  if (scene.spheres.size() == 0) r.fail("/spheres", "the scene has no spheres");
  scene.materials = table.take();
  return scene;
}

Scene read_scene_from(CountingInput::Source source, std::uint64_t max_bytes,
                      const std::string& name) {
  const std::string shown = one_line(name, 120);
  CountingInput input(std::move(source), max_bytes, shown);
  Scene scene = read_scene(Reader(shown), input);
  if (scene.name.empty()) scene.name = std::filesystem::path(name).stem().string();
  return scene;
}

// A float as the shortest decimal that reads back (through double, as JSON does) to it.
double shortest(float f) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, f);
  const double d = std::strtod(std::string(buffer, result.ptr).c_str(), nullptr);
  return float(d) == f ? d : double(f);
}

// Materials written from a scene are named by index. (Built with append: GCC 12 warns
// falsely, -Wrestrict, on "literal" + std::string.)
std::string material_key(std::size_t index) {
  std::string key = "m";
  key.append(std::to_string(index));
  return key;
}

ordered_json float3(const Vec3& v) {
  return {shortest(v.x), shortest(v.y), shortest(v.z)};
}
ordered_json double3(const Vec3d& v) {
  return {v.x, v.y, v.z};
}

ordered_json material_json(const Material& m) {
  if (const auto* l = std::get_if<Lambertian>(&m)) {
    return {{"type", "lambertian"}, {"albedo", float3(l->albedo)}};
  }
  if (const auto* metal = std::get_if<Metal>(&m)) {
    return {{"type", "metal"}, {"albedo", float3(metal->albedo)}, {"fuzz", shortest(metal->fuzz)}};
  }
  const Dielectric& d = std::get<Dielectric>(m);
  ordered_json j = {{"type", "dielectric"}, {"ior", shortest(d.ior)}};
  if (d.fresnel == FresnelModel::Exact) j["fresnel"] = "exact";  // Schlick is the default
  return j;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  std::size_t offset = 0;
  return read_scene_from(
      [&](char* buffer, std::size_t size) {
        const std::size_t n = std::min(size, text.size() - offset);
        std::memcpy(buffer, text.data() + offset, n);
        offset += n;
        return n;
      },
      limits::kMaxSceneFileBytes, source);
}

Scene load_scene_file(const std::string& path) {
  check_input_file(path, limits::kMaxSceneFileBytes, "scene file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw InvalidInput("scene file " + quote_value(path) + ": cannot open it");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(file, &std::fclose);
  return read_scene_from(
      [&](char* buffer, std::size_t size) {
        const std::size_t n = std::fread(buffer, 1, size, file);
        if (n == 0 && std::ferror(file)) {
          throw InvalidInput("scene file " + quote_value(path) + ": cannot read it");
        }
        return n;
      },
      limits::kMaxSceneFileBytes, path);
}

std::string scene_to_json(const Scene& scene) {
  // Written line by line rather than as one document: one material or sphere per line is
  // readable and diffable, and a million spheres take seconds, not a DOM of gigabytes.
  ordered_json head;
  head["version"] = kVersion;
  head["name"] = scene.name;
  if (scene.layout_seed) head["scene_seed"] = *scene.layout_seed;
  const CameraSettings& c = scene.camera;
  head["camera"] = {{"lookfrom", double3(c.lookfrom)}, {"lookat", double3(c.lookat)},
                    {"vup", double3(c.vup)},           {"vfov", c.vfov_degrees},
                    {"aperture", c.aperture},          {"focus_distance", c.focus_distance}};
  head["image"] = {{"width", scene.image.width},
                   {"aspect_ratio", scene.image.aspect_ratio},
                   {"spp", scene.image.samples_per_pixel},
                   {"depth", scene.image.max_depth}};
  head["background"] = {{"horizon", float3(scene.background.horizon)},
                        {"zenith", float3(scene.background.zenith)}};
  std::string out = "{\n";
  for (const auto& item : head.items()) {
    out.append("  ").append(ordered_json(item.key()).dump()).append(": ");
    out.append(item.value().dump()).append(",\n");
  }
  out.append("  \"materials\": {");
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    out.append(i ? ",\n    \"" : "\n    \"").append(material_key(i)).append("\": ");
    out.append(material_json(scene.materials[i]).dump());
  }
  out.append("\n  },\n  \"spheres\": [");
  const SphereSet& s = scene.spheres;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const ordered_json sphere = {{"center", float3(s.center(i))},
                                 {"radius", shortest(s.radius[i])},
                                 {"material", material_key(s.material[i])}};
    out.append(i ? ",\n    " : "\n    ").append(sphere.dump());
  }
  out.append("\n  ]\n}\n");
  return out;
}

}  // namespace rtiow

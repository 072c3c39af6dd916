#include "core/scene_file/scene_file.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_pipeline.h>
#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include "core/io/input_file.h"
#include "core/io/json_writer.h"
#include "core/limits/input_limits.h"
#include "core/parallel/cancellation.h"
#include "core/parallel/ieee_floating_point.h"
#include "core/parallel/thread_sanitizer.h"
#include "core/scene_file/json_float.h"
#include "core/scene_file/json_reader.h"
#include "core/scene_file/json_split.h"
#include "core/scene_file/json_stream.h"
#include "core/scene_file/material_json.h"
#include "core/scene_file/name_index.h"
#include "core/scene_file/rapidjson.h"
#include "core/scene_file/run_records.h"
#include "core/scene_file/sphere_json.h"

namespace rtiow {
namespace {

using scene_json::Place;
using scene_json::Reader;
using scene_json::shortest;

constexpr int kVersion = 1;

void read_camera(const Reader& r, const JsonValue& v, CameraSettings& cam) {
  const Place root;
  const Place p(root, "camera");
  r.object(v, p);
  r.only(v, p,
         {"lookfrom", "lookat", "vup", "vfov", "aperture", "defocus_angle", "focus_distance"});
  cam.lookfrom = r.vec3(r.require(v, p, "lookfrom"), Place(p, "lookfrom"));
  cam.lookat = r.vec3(r.require(v, p, "lookat"), Place(p, "lookat"));
  cam.vup = Vec3d{0, 1, 0};
  if (const JsonValue* vup = r.find(v, "vup")) cam.vup = r.vec3(*vup, Place(p, "vup"));
  cam.vfov_degrees = r.number(r.require(v, p, "vfov"), Place(p, "vfov"));
  cam.focus_distance = length(cam.lookat - cam.lookfrom);
  if (const JsonValue* f = r.find(v, "focus_distance")) {
    cam.focus_distance = r.bounded(*f, Place(p, "focus_distance"));
  }
  const JsonValue* aperture = r.find(v, "aperture");
  const JsonValue* angle = r.find(v, "defocus_angle");
  if (aperture && angle) r.fail(p, "give either \"aperture\" or \"defocus_angle\", not both");
  cam.aperture = 0.0;
  if (aperture) cam.aperture = r.bounded(*aperture, Place(p, "aperture"));
  if (angle) {
    // The book's later editions: the lens subtends this angle (degrees) from the focus plane.
    const double degrees = r.number(*angle, Place(p, "defocus_angle"));
    if (degrees < 0.0 || degrees >= 180.0) {
      r.fail(Place(p, "defocus_angle"), "must be in [0, 180), got " + Reader::format(degrees));
    }
    cam.aperture = 2.0 * focus_distance_of(cam) * std::tan(degrees * std::numbers::pi / 360.0);
  }
  try {
    validate(cam);
  } catch (const InvalidInput& e) {
    std::string what = e.what();
    if (what.rfind("camera: ", 0) == 0) what = what.substr(8);
    r.fail(p, what);
  }
}

void read_image(const Reader& r, const JsonValue& v, ImageSettings& image) {
  const Place root;
  const Place p(root, "image");
  r.object(v, p);
  r.only(v, p, {"width", "height", "aspect_ratio", "spp", "depth"});
  image.width = r.integer(r.require(v, p, "width"), Place(p, "width"), 1, limits::kMaxImageSide);
  const JsonValue* height = r.find(v, "height");
  const JsonValue* aspect = r.find(v, "aspect_ratio");
  if (height && aspect) r.fail(p, "give either \"height\" or \"aspect_ratio\", not both");
  if (!height && !aspect) r.fail(p, "missing field \"height\" (or \"aspect_ratio\")");
  if (height) {
    const int h = r.integer(*height, Place(p, "height"), 1, limits::kMaxImageSide);
    image.aspect_ratio = double(image.width) / double(h);
  } else {
    const Place at(p, "aspect_ratio");
    image.aspect_ratio = r.number(*aspect, at);
    if (image.aspect_ratio <= 0.0) r.fail(at, "must be > 0");
    // The height it implies must be a size rtiow renders: checked here, never clamped.
    const double h = height_for_width(image.width, image.aspect_ratio);
    if (!(h >= 1.0 && h <= double(limits::kMaxImageSide))) {
      r.fail(at, "gives a height of " + Reader::format(h) + " pixels for width " +
                     std::to_string(image.width) + " (must be 1 to " +
                     std::to_string(limits::kMaxImageSide) + ")");
    }
  }
  image.samples_per_pixel = 100;
  if (const JsonValue* spp = r.find(v, "spp")) {
    image.samples_per_pixel = r.integer(*spp, Place(p, "spp"), 1, std::numeric_limits<int>::max());
  }
  image.max_depth = 50;
  if (const JsonValue* depth = r.find(v, "depth"))
    image.max_depth = r.integer(*depth, Place(p, "depth"), 0, limits::kMaxDepth);
}

// Material names to indices. Spheres may name a material before /materials defines it
// (keys have no order), so a name gets its index when first seen by either.
//
// Each name is resolved one element later than it is read: its table slot is prefetched
// meanwhile, hiding the miss (300 ns) behind the parse of the next element (1 us). On a
// million-material scene that is 0.6 s of a 2.5 s load.
class MaterialTable {
 public:
  MaterialTable(const Reader& r, SphereSet& spheres) : r_(r), spheres_(spheres) {}

  // `hash`: NameIndex::hash(name), which a caller may have computed on another core. The name
  // is copied: it is resolved when the next one comes.
  void define(std::string_view name, std::uint64_t hash, const Material& m) {
    resolve_pending();
    pending_ = {Pending::kDefine, std::string(name), hash, m, 0};
    names_.prefetch(hash);
  }

  // Sets the material of sphere `sphere` (already added) to the one named.
  void refer(std::string_view name, std::uint64_t hash, std::size_t sphere) {
    resolve_pending();
    pending_ = {Pending::kRefer, std::string(name), hash, {}, sphere};
    names_.prefetch(hash);
  }

  // Resolves the name read last. Call it before reading the next element, so that its error
  // (a duplicate name) comes before any error of the next.
  void resolve_pending() {
    const Pending::Kind kind = std::exchange(pending_.kind, Pending::kNone);
    if (kind == Pending::kDefine) define_now(pending_.name, pending_.hash, pending_.material);
    if (kind == Pending::kRefer) refer_now(pending_.name, pending_.hash, pending_.sphere);
  }

  // define() and refer() at once, for a caller that hides the table's misses itself (by
  // prefetch(), some names ahead).
  void define_now(std::string_view name, std::uint64_t hash, const Material& m) {
    const std::uint32_t index = lookup(name, hash);
    if (uses_[index] == Use::kDefined) {
      const Place root;
      const Place materials(root, "materials");
      r_.fail(Place(materials, name), "a second material of this name (duplicate key)");
    }
    uses_[index] = Use::kDefined;
    materials_[index] = m;
  }
  void refer_now(std::string_view name, std::uint64_t hash, std::size_t sphere) {
    const std::uint32_t index = lookup(name, hash);
    spheres_.material[sphere] = index;
    if (uses_[index] == Use::kNone) {
      uses_[index] = Use::kReferred;
      first_users_.push_back({index, sphere});
    }
  }

  // Starts loading where a name of this hash will be looked up.
  void prefetch(std::uint64_t hash) const { names_.prefetch(hash); }

  // All materials, once every name a sphere used is defined.
  std::vector<Material> take() {
    resolve_pending();
    const auto undefined = std::find(uses_.begin(), uses_.end(), Use::kReferred);
    if (undefined != uses_.end()) {
      const auto index = std::uint32_t(undefined - uses_.begin());
      const auto user = std::find_if(first_users_.begin(), first_users_.end(),
                                     [&](const auto& first) { return first.first == index; });
      const Place root;
      const Place spheres(root, "spheres");
      const Place sphere(spheres, user->second);
      r_.fail(Place(sphere, "material"),
              "no material named " + quote_value(names_.name(index), 40) + " in /materials");
    }
    return std::move(materials_);
  }

 private:
  // What has been seen of a name: only spheres referring to it (the first is kept in
  // first_users_), or its definition.
  enum class Use : std::uint8_t { kNone, kReferred, kDefined };
  struct Pending {
    enum Kind { kNone, kDefine, kRefer } kind = kNone;
    std::string name;
    std::uint64_t hash = 0;
    Material material{Lambertian{}};
    std::size_t sphere = 0;
  };

  std::uint32_t lookup(std::string_view name, std::uint64_t hash) {
    if (names_.size() >= std::numeric_limits<std::uint32_t>::max()) {
      r_.fail(Place(), "more materials than rtiow indexes");
    }
    const std::uint32_t index = names_.intern(name, hash);
    if (index == uses_.size()) {
      uses_.push_back(Use::kNone);
      materials_.emplace_back(Lambertian{});
    }
    return index;
  }

  // By name index, in arrays of their own rather than one of records: a million names' table
  // is copied each time it doubles, and the materials are the scene's as they stand.
  const Reader& r_;
  SphereSet& spheres_;
  NameIndex names_;
  std::vector<Material> materials_;
  std::vector<Use> uses_;
  std::vector<std::pair<std::uint32_t, std::size_t>> first_users_;  // (name, sphere)
  Pending pending_;
};

// `hash`: of the sphere's material name (NameIndex::hash).
void add_sphere(const SphereRecord& s, std::uint64_t hash, MaterialTable& table,
                SphereSet& spheres) {
  spheres.add(s.center, s.radius, 0);
  table.refer(s.material, hash, spheres.size() - 1);
}

const Place kRootAt;
const Place kMaterialsAt(kRootAt, "materials"), kSpheresAt(kRootAt, "spheres");

// The streamed containers: materials and spheres are converted as they are parsed and their
// text dropped.
std::map<std::string, StreamedMember, std::less<>> streamed_members(const Reader& r,
                                                                    MaterialTable& table,
                                                                    SphereSet& spheres) {
  std::map<std::string, StreamedMember, std::less<>> streamed;
  streamed["materials"] = {true, [&](std::string_view key, std::size_t, const JsonValue& v) {
                             table.resolve_pending();
                             table.define(key, NameIndex::hash(key),
                                          read_material(r, v, Place(kMaterialsAt, key)));
                           }};
  streamed["spheres"] = {false, [&](std::string_view, std::size_t i, const JsonValue& v) {
                           table.resolve_pending();
                           const SphereRecord sphere = read_sphere(r, v, Place(kSpheresAt, i));
                           add_sphere(sphere, NameIndex::hash(sphere.material), table, spheres);
                         }};
  return streamed;
}

// The rest of a parsed scene (camera, image, background: small), read at the end into
// `scene`, whose spheres `table` refers to.
void finish_scene(const Reader& r, const JsonDocument& root, Scene& scene, MaterialTable& table) {
  r.object(root, kRootAt);
  r.only(
      root, kRootAt,
      {"version", "name", "scene_seed", "camera", "image", "background", "materials", "spheres"});
  const JsonValue& version = r.require(root, kRootAt, "version");
  if (!version.IsNumber() || !version.IsInt() || version.GetInt() != kVersion) {
    r.fail(Place(kRootAt, "version"), "this rtiow reads scene format version " +
                                          std::to_string(kVersion) + ", got " +
                                          Reader::describe(version));
  }
  if (const JsonValue* name = r.find(root, "name")) {
    scene.name = r.string(*name, Place(kRootAt, "name"), "a string");
  }
  if (const JsonValue* seed = r.find(root, "scene_seed")) {
    if (!seed->IsUint64()) r.fail(Place(kRootAt, "scene_seed"), "must be a whole number >= 0");
    scene.layout_seed = seed->GetUint64();
  }
  read_camera(r, r.require(root, kRootAt, "camera"), scene.camera);
  read_image(r, r.require(root, kRootAt, "image"), scene.image);

  if (const JsonValue* bg = r.find(root, "background")) {
    const Place at(kRootAt, "background");
    r.object(*bg, at);
    r.only(*bg, at, {"horizon", "zenith"});
    scene.background.horizon = r.color(r.require(*bg, at, "horizon"), Place(at, "horizon"));
    scene.background.zenith = r.color(r.require(*bg, at, "zenith"), Place(at, "zenith"));
  }

  r.object(r.require(root, kRootAt, "materials"), kMaterialsAt);
  const JsonValue& spheres = r.require(root, kRootAt, "spheres");
  if (!spheres.IsArray()) {
    r.fail(kSpheresAt, "must be an array, got " + Reader::describe(spheres));
  }
  if (scene.spheres.size() == 0) r.fail(kSpheresAt, "the scene has no spheres");
  scene.materials = table.take();
}

// Reads a scene from a stream, in one piece.
Scene read_scene(const Reader& r, JsonInput& input) {
  Scene scene;
  MaterialTable table(r, scene.spheres);
  JsonDocument root;
  parse_json_stream(input, r.source(), streamed_members(r, table, scene.spheres), root);
  finish_scene(r, root, scene, table);
  return scene;
}

// A window's runs and what they read to.
struct WindowRecords {
  std::shared_ptr<std::string> text;  // the window, kept until the records' names are resolved
  std::vector<MemberRun> runs;
  RunRecords records;
};

// Adds a window's records to the table and the spheres in document order, prefetching the
// table's slots some names ahead.
void add_records(const WindowRecords& window, MaterialTable& table, SphereSet& spheres) {
  constexpr std::size_t kAhead = 16;
  const RunRecords& records = window.records;
  const std::vector<std::uint64_t>& hashes = records.hashes;
  std::size_t name = 0, material = 0, sphere = 0;
  for (const MemberRun& run : window.runs) {
    const bool materials = run.key == "materials";
    for (std::size_t k = 0; k < run.members; ++k, ++name) {
      if (name + kAhead < hashes.size()) table.prefetch(hashes[name + kAhead]);
      if (materials) {
        const MaterialRecord& m = records.materials[material++];
        table.define_now(m.name, hashes[name], m.material);
      } else {
        const SphereRecord& s = records.spheres[sphere++];
        spheres.add(s.center, s.radius, 0);
        table.refer_now(s.material, hashes[name], spheres.size() - 1);
      }
    }
  }
}

}  // namespace

namespace {

// The split read's three stages with windows in flight between them: cut (in order), read (on
// any core), resolve the names (in order, as the one-piece read does). A failure is a flag
// rather than an exception, which would leave the windows in flight undestroyed: the stages
// after it pass their windows on untouched, and the cut stops.
// (TSan cannot see TBB's own ordering of the stages: the annotations state it.)
class RunPipeline {
 public:
  RunPipeline(JsonSplitter& splitter, const JsonSplitter::Source& source, MaterialTable& table,
              SphereSet& spheres)
      : splitter_(splitter), source_(source), table_(table), spheres_(spheres) {}

  // Runs the stages; false where a window could not be cut, read or resolved. `skeleton`: the
  // document with its split containers left empty.
  bool run(std::string& skeleton) {
    skeleton_ = &skeleton;
    const auto cut_stage = [this](tbb::flow_control& c) { return cut_window(c); };
    const auto read_stage = [this](Window w) { return read_window(w); };
    const auto resolve_stage = [this](Window w) { resolve_window(w); };
    const auto cut = tbb::make_filter<void, Window>(tbb::filter_mode::serial_in_order,
                                                    TsanPipelineStage(cut_stage));
    const auto read =
        tbb::make_filter<Window, Window>(tbb::filter_mode::parallel, TsanPipelineStage(read_stage));
    const auto resolve = tbb::make_filter<Window, void>(tbb::filter_mode::serial_in_order,
                                                        TsanPipelineStage(resolve_stage));
    const auto tokens = std::size_t(2 * tbb::this_task_arena::max_concurrency());
    // The stages' tasks convert numbers under IEEE's settings (ieee_floating_point.h), as
    // the one-piece read does, whatever the arena's.
    tbb::task_group_context context(
        tbb::task_group_context::bound,
        tbb::task_group_context::default_traits | tbb::task_group_context::fp_settings);
    tsan_release(&tsan_fork_sync);
    tbb::parallel_pipeline(tokens, cut & read & resolve, context);
    tsan_acquire(&tsan_join_sync);
    return !failed_;
  }

 private:
  // Windows pass between the stages as plain pointers (TBB's copies of them are its own
  // business), owned by the stage that holds them.
  using Window = WindowRecords*;

  Window cut_window(tbb::flow_control& control) {
    tsan_acquire(&tsan_fork_sync);
    tsan_acquire(&cut_order_);
    std::unique_ptr<WindowRecords> records;
    if (done_ || failed_) {
      control.stop();
    } else {
      SplitWindow window;
      if (!splitter_.next(source_, limits::kMaxSceneFileBytes, window, done_, *skeleton_)) {
        failed_ = true;
      }
      records = std::make_unique<WindowRecords>();
      records->text = std::move(window.text);
      records->runs = std::move(window.runs);
    }
    tsan_release(&cut_order_);
    tsan_release(&tsan_join_sync);
    return records.release();
  }

  Window read_window(Window records) {
    tsan_acquire(&cut_order_);
    for (const MemberRun& run : records->runs) {
      if (failed_ || !read_run_records(*records->text, run, records->records)) {
        failed_ = true;
        break;
      }
    }
    tsan_release(&read_order_);
    return records;
  }

  void resolve_window(Window window) {
    const std::unique_ptr<WindowRecords> records(window);
    tsan_acquire(&read_order_);
    tsan_acquire(&resolve_order_);
    if (!failed_) {
      try {
        add_records(*records, table_, spheres_);  // refuses a material named twice
      } catch (const InvalidInput&) {
        failed_ = true;
      }
    }
    tsan_release(&resolve_order_);
    tsan_release(&tsan_join_sync);
  }

  JsonSplitter& splitter_;
  const JsonSplitter::Source& source_;
  MaterialTable& table_;
  SphereSet& spheres_;
  std::string* skeleton_ = nullptr;
  bool done_ = false;
  std::atomic<bool> failed_{false};
  char cut_order_ = 0, read_order_ = 0, resolve_order_ = 0;
};

// The scene's members outside the split containers, read from the skeleton the cut left.
void read_skeleton(const Reader& r, const std::string& skeleton, Scene& scene,
                   MaterialTable& table) {
  // The skeleton's split containers are empty: a member there means the scan was wrong.
  std::map<std::string, StreamedMember, std::less<>> streamed;
  for (const char* key : {"materials", "spheres"}) {
    streamed[key] = {std::string_view(key) == "materials",
                     [](std::string_view, std::size_t, const JsonValue&) {
                       throw InvalidInput("a member left in the skeleton");
                     }};
  }
  JsonInput input(JsonInput::from_text(skeleton), limits::kMaxSceneFileBytes, r.source());
  JsonDocument root;
  parse_json_stream(input, r.source(), streamed, root);
  finish_scene(r, root, scene, table);
}

}  // namespace

std::optional<Scene> read_scene_in_runs(const JsonSplitter::Source& source, const std::string& name,
                                        std::size_t run_bytes, std::size_t window_bytes) {
  const IeeeFloatingPoint ieee;
  const Reader r(one_line(name, 120));
  Scene scene;
  MaterialTable table(r, scene.spheres);
  JsonSplitter splitter({{"materials", '{'}, {"spheres", '['}}, run_bytes, window_bytes);
  std::string skeleton;
  try {
    if (!RunPipeline(splitter, source, table, scene.spheres).run(skeleton)) return std::nullopt;
    read_skeleton(r, skeleton, scene, table);
    if (scene.name.empty()) scene.name = std::filesystem::path(name).stem().string();
    return scene;
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

namespace {

Scene read_scene_from(JsonInput::Source source, std::uint64_t max_bytes, const std::string& name) {
  const IeeeFloatingPoint ieee;  // as the split read (read_scene_in_runs)
  const std::string shown = one_line(name, 120);
  JsonInput input(std::move(source), max_bytes, shown);
  Scene scene = read_scene(Reader(shown), input);
  if (scene.name.empty()) scene.name = std::filesystem::path(name).stem().string();
  return scene;
}

// Materials written from a scene are named by index: "m" and the index.
void append_material_key(std::string& out, std::size_t index) {
  char digits[24];
  out.push_back('m');
  out.append(digits, std::to_chars(digits, digits + sizeof digits, index).ptr);
}

void write_float3(JsonWriter& out, const Vec3& v) {
  out.begin_array().number(shortest(v.x)).number(shortest(v.y)).number(shortest(v.z)).end();
}
void write_double3(JsonWriter& out, const Vec3d& v) {
  out.begin_array().number(v.x).number(v.y).number(v.z).end();
}

// Hands `sink` the text of items [0, n) in order, each item's written by `format(i, text)`:
// blocks of items are formatted on every core (a million spheres' numbers are most of a big
// scene's writing time), a bounded batch of blocks at a time, and passed on in order.
template <typename Format>
void write_lines_in_parallel(std::size_t n, const std::function<void(std::string_view)>& sink,
                             const Format& format) {
  constexpr std::size_t kBlock = 2048, kBlocksPerBatch = 64;
  std::vector<std::string> blocks(kBlocksPerBatch);
  for (std::size_t first = 0; first < n; first += kBlock * kBlocksPerBatch) {
    const std::size_t count = std::min(kBlocksPerBatch, (n - first + kBlock - 1) / kBlock);
    const auto format_blocks = [&](const tbb::blocked_range<std::size_t>& part) {
      for (std::size_t b = part.begin(); b < part.end(); ++b) {
        std::string& text = blocks[b];
        text.clear();
        const std::size_t begin = first + b * kBlock, end = std::min(n, begin + kBlock);
        for (std::size_t i = begin; i < end; ++i) format(i, text);
      }
    };
    // TSan cannot see TBB's fork and join: the annotations state them.
    tsan_release(&tsan_fork_sync);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                      TsanOrderedBody<decltype(format_blocks)>(format_blocks),
                      tbb::simple_partitioner());
    tsan_acquire(&tsan_join_sync);
    for (std::size_t b = 0; b < count; ++b) sink(blocks[b]);
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  return read_scene_from(JsonInput::from_text(text), limits::kMaxSceneFileBytes, source);
}

namespace {

// A scene file is a JSON object: its first character (after white space) is '{'. A file
// that begins otherwise (an image, a file of zeros, a log) is refused from those bytes, in
// words that say what it is, rather than by a parse error at line 1.
void check_begins_as_a_scene(const std::string& first, const std::string& path) {
  std::size_t at = first.rfind("\xef\xbb\xbf", 0) == 0 ? 3 : 0;  // a UTF-8 byte-order mark
  while (at < first.size() &&
         (first[at] == ' ' || first[at] == '\t' || first[at] == '\n' || first[at] == '\r')) {
    ++at;
  }
  if (at == first.size() || first[at] == '{') return;  // empty, or a parse error says where
  char shown[8];
  std::snprintf(shown, sizeof shown, "0x%02x", static_cast<unsigned char>(first[at]));
  const bool printable = first[at] >= 0x21 && first[at] <= 0x7e;
  throw InvalidInput("scene file " + quote_value(path) +
                     ": is not a scene file: a scene file is a JSON object, beginning with '{', "
                     "and this one begins with " +
                     (printable ? quote_value(std::string(1, first[at])) : std::string(shown)));
}

}  // namespace

Scene load_scene_file(const std::string& path) {
  if (path == "-") {  // `rtiow scene cover | rtiow render -`
    return read_scene_from(
        [](char* buffer, std::size_t size) {
          const std::size_t n = std::fread(buffer, 1, size, stdin);
          if (n == 0 && std::ferror(stdin)) {
            throw InvalidInput("scene from standard input: cannot read it");
          }
          return n;
        },
        limits::kMaxSceneFileBytes, "standard input");
  }
  InputFile input(path, limits::kMaxSceneFileBytes, "scene file");
  check_begins_as_a_scene(input.first_bytes(4096), path);
  const std::uint64_t bytes = input.size();
  std::FILE* file = ::fdopen(input.fd(), "rb");
  if (!file) throw InvalidInput("scene file " + quote_value(path) + ": cannot open it");
  input.release();  // the FILE closes it
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(file, &std::fclose);
  const auto read = [&](char* buffer, std::size_t size) {
    throw_if_cancelled();  // a file of gigabytes: a stop asked for is honoured between buffers
    const std::size_t n = std::fread(buffer, 1, size, file);
    if (n == 0 && std::ferror(file)) {
      throw InvalidInput("scene file " + quote_value(path) + ": cannot read it");
    }
    return n;
  };
  // A big file is parsed in runs, on every core; if that fails, or the file is not one it can
  // cut, it is read again in one piece, which says what is wrong and where.
  if (bytes >= kSplitFileBytes) {
    if (std::optional<Scene> scene =
            read_scene_in_runs(read, path, kSplitRunBytes, kSplitWindowBytes)) {
      return std::move(*scene);
    }
    std::rewind(file);
    std::clearerr(file);
  }
  return read_scene_from(read, limits::kMaxSceneFileBytes, path);
}

// The settings before the materials, one per line: each as `"key": value` with its value on
// one line, as nlohmann-json writes it.
std::string scene_settings_json(const Scene& scene) {
  std::string text = "{\n";
  const auto member = [&](const char* key, const std::function<void(JsonWriter&)>& value) {
    JsonWriter one;
    value(one);
    text.append("  ").append(json_quoted(key)).append(": ").append(one.text()).append(",\n");
  };
  member("version", [](JsonWriter& v) { v.whole(kVersion); });
  member("name", [&](JsonWriter& v) { v.string(scene.name); });
  if (scene.layout_seed) member("scene_seed", [&](JsonWriter& v) { v.whole(*scene.layout_seed); });
  const CameraSettings& c = scene.camera;
  member("camera", [&](JsonWriter& v) {
    v.begin_object();
    write_double3(v.key("lookfrom"), c.lookfrom);
    write_double3(v.key("lookat"), c.lookat);
    write_double3(v.key("vup"), c.vup);
    v.key("vfov").number(c.vfov_degrees);
    v.key("aperture").number(c.aperture);
    v.key("focus_distance").number(focus_distance_of(c));
    v.end();
  });
  member("image", [&](JsonWriter& v) {
    v.begin_object();
    v.key("width").whole(scene.image.width);
    v.key("aspect_ratio").number(scene.image.aspect_ratio);
    v.key("spp").whole(scene.image.samples_per_pixel);
    v.key("depth").whole(scene.image.max_depth);
    v.end();
  });
  member("background", [&](JsonWriter& v) {
    v.begin_object();
    write_float3(v.key("horizon"), scene.background.horizon);
    write_float3(v.key("zenith"), scene.background.zenith);
    v.end();
  });
  return text;
}

void write_scene_json(const Scene& scene, const std::function<void(std::string_view)>& sink) {
  // Written line by line rather than as one document: one material or sphere per line is
  // readable and diffable, and a million spheres take seconds, not a DOM of gigabytes.
  sink(scene_settings_json(scene).append("  \"materials\": {"));
  write_lines_in_parallel(scene.materials.size(), sink, [&](std::size_t i, std::string& out) {
    out.append(i ? ",\n    \"" : "\n    \"");
    append_material_key(out, i);
    out.append("\": ");
    out.append(material_to_json(scene.materials[i]));
  });
  sink("\n  },\n  \"spheres\": [");
  const SphereSet& s = scene.spheres;
  // Each sphere as nlohmann-json writes {"center":[x,y,z],"radius":r,"material":"mN"}, built
  // without a JSON object per sphere (most of a million-sphere scene's time).
  write_lines_in_parallel(s.size(), sink, [&](std::size_t i, std::string& out) {
    out.append(i ? ",\n    " : "\n    ").append("{\"center\":[");
    append_json_float(out, s.center_x[i]);
    out.push_back(',');
    append_json_float(out, s.center_y[i]);
    out.push_back(',');
    append_json_float(out, s.center_z[i]);
    out.append("],\"radius\":");
    append_json_float(out, s.radius[i]);
    out.append(",\"material\":\"");
    append_material_key(out, s.material[i]);
    out.append("\"}");
  });
  sink("\n  ]\n}\n");
}

std::string scene_to_json(const Scene& scene) {
  std::string out;
  // Under 96 characters a material or a sphere: one allocation, not a copy per doubling.
  out.reserve(1024 + 96 * (scene.materials.size() + scene.spheres.size()));
  write_scene_json(scene, [&](std::string_view piece) { out.append(piece); });
  return out;
}

}  // namespace rtiow

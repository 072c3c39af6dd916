#include "python/render_options.h"

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/nearest_name.h"
#include "core/limits/setting_name.h"
#include "core/render/first_hit_passes.h"
#include "core/session/tev_display.h"

namespace py = pybind11;

namespace rtiow::python {
namespace {

// "spp=2.5: expected a whole number" and the like.
[[noreturn]] void refuse(const std::string& name, const py::handle& value,
                         const std::string& what) {
  throw InvalidInput(setting(name, py::repr(value).cast<std::string>()) + ": expected " + what);
}

// A whole number, not a bool (which Python counts as one), within [least, most].
long long whole(const std::string& name, const py::handle& value, long long least, long long most) {
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value)) {
    refuse(name, value, "a whole number");
  }
  long long n = 0;
  try {
    n = value.cast<long long>();
  } catch (const py::cast_error&) {
    refuse(name, value,
           "a whole number from " + std::to_string(least) + " to " + std::to_string(most));
  }
  if (n < least || n > most) {
    refuse(name, value,
           "a whole number from " + std::to_string(least) + " to " + std::to_string(most));
  }
  return n;
}

// A finite number >= 0 (an int or a float).
double number(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::bool_>(value) ||
      !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))) {
    refuse(name, value, "a number");
  }
  const double x = value.cast<double>();
  if (!std::isfinite(x) || x < 0.0) refuse(name, value, "a finite number >= 0");
  return x;
}

bool flag(const std::string& name, const py::handle& value) {
  if (!py::isinstance<py::bool_>(value)) refuse(name, value, "True or False");
  return value.cast<bool>();
}

std::string text(const std::string& name, const py::handle& value) {
  if (!py::isinstance<py::str>(value)) refuse(name, value, "a string");
  return value.cast<std::string>();
}

// Numbers as a sequence, or as the command line's comma-separated text.
std::vector<double> numbers(const std::string& name, const py::handle& value, std::size_t count) {
  std::vector<double> out;
  if (py::isinstance<py::str>(value)) {
    std::string word;
    for (const char c : value.cast<std::string>() + ",") {
      if (c != ',') {
        word.push_back(c);
        continue;
      }
      try {
        std::size_t used = 0;
        out.push_back(std::stod(word, &used));
        if (used != word.size()) throw std::invalid_argument(word);
      } catch (const std::exception&) {
        refuse(name, value, std::to_string(count) + " numbers");
      }
      word.clear();
    }
  } else if (py::isinstance<py::sequence>(value)) {
    for (const py::handle& item : value.cast<py::sequence>()) {
      if (py::isinstance<py::bool_>(item) ||
          !(py::isinstance<py::int_>(item) || py::isinstance<py::float_>(item))) {
        refuse(name, value, std::to_string(count) + " numbers");
      }
      out.push_back(item.cast<double>());
    }
  }
  if (out.size() != count) refuse(name, value, std::to_string(count) + " numbers");
  for (const double x : out) {
    if (!std::isfinite(x)) refuse(name, value, std::to_string(count) + " finite numbers");
  }
  return out;
}

Vec3d vector3(const std::string& name, const py::handle& value) {
  const std::vector<double> v = numbers(name, value, 3);
  return {v[0], v[1], v[2]};
}

using Setter = std::function<void(RenderRequest&, const std::string&, const py::handle&)>;
using SetterTable = std::map<std::string, Setter>;
constexpr long long kMaxInt = 2147483647;

// The size, the samples and how they are taken.
void add_sampling_setters(SetterTable& table) {
  table.insert({
      {"width", [](RenderRequest& r, auto& n, auto& v) { r.width = int(whole(n, v, 0, kMaxInt)); }},
      {"height",
       [](RenderRequest& r, auto& n, auto& v) { r.height = int(whole(n, v, 0, kMaxInt)); }},
      {"spp", [](RenderRequest& r, auto& n, auto& v) { r.spp = int(whole(n, v, 0, kMaxInt)); }},
      {"depth",
       [](RenderRequest& r, auto& n, auto& v) { r.max_depth = int(whole(n, v, 0, kMaxInt)); }},
      {"seed",
       [](RenderRequest& r, auto& n, auto& v) {
         if (py::isinstance<py::bool_>(v) || !py::isinstance<py::int_>(v)) {
           refuse(n, v, "a whole number from 0 to 2^64 - 1");
         }
         try {
           r.seed = v.template cast<std::uint64_t>();
         } catch (const py::cast_error&) {
           refuse(n, v, "a whole number from 0 to 2^64 - 1");
         }
       }},
      {"threads",
       [](RenderRequest& r, auto& n, auto& v) { r.threads = int(whole(n, v, 0, kMaxInt)); }},
      {"min_spp",
       [](RenderRequest& r, auto& n, auto& v) { r.min_samples = int(whole(n, v, 0, kMaxInt)); }},
      {"time_limit",
       [](RenderRequest& r, auto& n, auto& v) { r.time_limit_seconds = number(n, v); }},
      {"target_error", [](RenderRequest& r, auto& n, auto& v) { r.target_error = number(n, v); }},
      {"image_error", [](RenderRequest& r, auto& n, auto& v) { r.image_error = number(n, v); }},
      {"adaptive", [](RenderRequest& r, auto& n, auto& v) { r.adaptive = flag(n, v); }},
      {"stats_channels", [](RenderRequest& r, auto& n, auto& v) { r.estimate_error = flag(n, v); }},
  });
}

// The path's rules, the passes, the region and the camera.
void add_scene_setters(SetterTable& table) {
  table.insert({
      {"roulette",
       [](RenderRequest& r, auto& n, auto& v) {
         if (py::isinstance<py::bool_>(v)) {
           r.russian_roulette = v.template cast<bool>();
           return;
         }
         const std::string t = text(n, v);
         if (t != roulette_name(true) && t != roulette_name(false)) refuse(n, v, "'on' or 'off'");
         r.russian_roulette = t == roulette_name(true);
       }},
      {"sampler",
       [](RenderRequest& r, auto& n, auto& v) { r.sampler = parse_sampler(text(n, v)); }},
      {"accel", [](RenderRequest& r, auto& n, auto& v) { r.accel = parse_accel(text(n, v)); }},
      {"fresnel",
       [](RenderRequest& r, auto& n, auto& v) {
         const auto model = parse_fresnel(text(n, v));
         if (!model) refuse(n, v, "'schlick' or 'exact'");
         r.fresnel = *model;
       }},
      {"passes",
       [](RenderRequest& r, auto& n, auto& v) {
         std::string list;
         if (py::isinstance<py::str>(v)) {
           list = v.template cast<std::string>();
         } else if (py::isinstance<py::sequence>(v)) {
           for (const py::handle& item : v.template cast<py::sequence>()) {
             list += (list.empty() ? "" : ",") + text(n, item);
           }
         } else {
           refuse(n, v, "pass names (albedo, normal, depth)");
         }
         try {
           r.passes = parse_passes(list);
         } catch (const InvalidInput& e) {
           throw InvalidInput(setting(n) + ": " + e.what());
         }
       }},
      {"crop",
       [](RenderRequest& r, auto& n, auto& v) {
         const std::vector<double> c = numbers(n, v, 4);
         for (const double x : c) {
           if (x != std::floor(x) || x < 0 || x > double(kMaxInt)) {
             refuse(n, v, "four whole numbers x0, y0, x1, y1");
           }
         }
         r.crop = PixelRegion{int(c[0]), int(c[1]), int(c[2]), int(c[3])};
       }},
      {"lookfrom", [](RenderRequest& r, auto& n, auto& v) { r.camera.lookfrom = vector3(n, v); }},
      {"lookat", [](RenderRequest& r, auto& n, auto& v) { r.camera.lookat = vector3(n, v); }},
      {"vup", [](RenderRequest& r, auto& n, auto& v) { r.camera.vup = vector3(n, v); }},
      {"vfov", [](RenderRequest& r, auto& n, auto& v) { r.camera.vfov_degrees = number(n, v); }},
      {"aperture", [](RenderRequest& r, auto& n, auto& v) { r.camera.aperture = number(n, v); }},
      {"focus_distance",
       [](RenderRequest& r, auto& n, auto& v) { r.camera.focus_distance = number(n, v); }},
  });
}

// Every option rtiow.render() takes, by the library's name for it.
const SetterTable& setters() {
  static const SetterTable table = [] {
    SetterTable t;
    add_sampling_setters(t);
    add_scene_setters(t);
    return t;
  }();
  return table;
}

using SessionSetter = std::function<void(ParsedOptions&, const std::string&, const py::handle&)>;

// The options of a render to a file and of a share of the samples.
const std::map<std::string, SessionSetter>& session_setters() {
  static const std::map<std::string, SessionSetter> table = {
      {"output", [](ParsedOptions& o, auto& n,
                    auto& v) { o.job.output = text(n, v), o.job.output_given = true; }},
      {"part", [](ParsedOptions& o, auto& n, auto& v) { o.job.part = text(n, v); }},
      {"sample_range", [](ParsedOptions& o, auto& n, auto& v) { o.job.sample_range = text(n, v); }},
      {"resume",
       [](ParsedOptions& o, auto& n, auto& v) { o.session.checkpoint.resume = flag(n, v); }},
      {"restart",
       [](ParsedOptions& o, auto& n, auto& v) { o.session.checkpoint.restart = flag(n, v); }},
      {"keep_state",
       [](ParsedOptions& o, auto& n, auto& v) { o.session.checkpoint.keep_state = flag(n, v); }},
      {"checkpoint", [](ParsedOptions& o, auto& n,
                        auto& v) { o.session.checkpoint.interval_seconds = number(n, v); }},
      {"preview",
       [](ParsedOptions& o, auto& n, auto& v) { o.session.preview_seconds = number(n, v); }},
      {"display", [](ParsedOptions& o, auto& n,
                     auto& v) { o.session.display = parse_display_address(text(n, v)); }},
      {"reproducible",
       [](ParsedOptions& o, auto& n, auto& v) { o.session.reproducible = flag(n, v); }},
      {"denoise", [](ParsedOptions& o, auto& n, auto& v) { o.job.denoise = flag(n, v); }},
  };
  return table;
}

}  // namespace

ParsedOptions parse_render_options(const py::kwargs& options) {
  ParsedOptions parsed;
  parsed.session.checkpoint.quiet = true;  // where the samples went is the exception's note
  std::vector<std::string> known;
  for (const auto& [name, setter] : setters()) known.push_back(name);
  for (const auto& [name, setter] : session_setters()) known.push_back(name);
  for (const auto& [key, value] : options) {
    const std::string name = key.cast<std::string>();
    if (const auto found = setters().find(name); found != setters().end()) {
      found->second(parsed.job.request, name, value);
    } else if (const auto session = session_setters().find(name);
               session != session_setters().end()) {
      session->second(parsed, name, value);
    } else {
      throw InvalidInput("render() has no option " + quote_value(name) + did_you_mean(name, known));
    }
  }
  parsed.job.stats_channels = parsed.job.request.estimate_error;
  const bool to_file = parsed.job.output_given;
  for (const auto& [name, given] : {std::pair{"resume", parsed.session.checkpoint.resume},
                                    std::pair{"restart", parsed.session.checkpoint.restart},
                                    std::pair{"keep_state", parsed.session.checkpoint.keep_state},
                                    std::pair{"preview", parsed.session.preview_seconds > 0.0},
                                    std::pair{"display", parsed.session.display.has_value()}}) {
    if (given && !to_file) {
      throw InvalidInput(setting(name) + " is for a render to a file: give " + setting("output"));
    }
  }
  return parsed;
}

}  // namespace rtiow::python

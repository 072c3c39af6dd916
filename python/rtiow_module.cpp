// The compiled part of the Python module `rtiow` (rtiow._rtiow): scenes, renders and image
// comparison from the library (core/rtiow.h), in Python's words with the command line's names:
// a render's keyword arguments are `rtiow render`'s long options (`--time-limit` is
// `time_limit`), and its messages name them so (core/limits/setting_name.h's library spelling).
// A render runs on a thread of its own with the GIL released; the caller's thread wakes every
// 50 ms to look for a signal (Ctrl-C stops the render and raises KeyboardInterrupt) and to call
// the progress callback. Images are numpy arrays over the result's own memory, not copies.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/compare/image_comparison.h"
#include "core/compare/image_diff.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/nearest_name.h"
#include "core/render/recorded_request.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"
#include "core/render/sample_share.h"
#include "core/rtiow.h"
#include "core/session/progress_status.h"
#include "core/session/render_session.h"
#include "core/session/render_summary.h"
#include "core/session/session_report.h"
#include "python/render_options.h"
#include "python/watched_work.h"

namespace py = pybind11;

namespace rtiow::python {
namespace {

// A finished render with what it was a render of, so it can describe and write itself.
struct Render {
  Scene scene;
  RenderSettings settings;
  RenderResult result;
  bool stats_channels = false;
  bool passes_asked = false;              // passes the caller named (denoise=True keeps them all)
  bool share = false;                     // a share of the samples: written as a part file
  std::uint64_t samples_asked = 0;        // the whole job's count, which the shares are cut from
  std::string written;                    // rendered with output=: where the image or part went
  std::optional<DenoisedImage> denoised;  // denoise=True: the image and its estimates
};

// denoise=True for a render held in memory: the denoiser's image and estimates, or a warning
// (a render stopped before each half of every pixel had a sample keeps its noisy image).
void denoise_in_memory(Render& render) {
  const std::string missing = why_not_denoised(render.result);
  if (!missing.empty()) {
    const std::string warning = "the image is not denoised: " + missing;
    if (PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 1) != 0) throw py::error_already_set();
    return;
  }
  render.denoised = interruptible<DenoisedImage>([&](const std::function<bool()>& cancelled) {
    return denoised_image(render.result, DenoiseControl{cancelled});
  });
  if (render.denoised) take_delivered_estimate(render.settings, render.result, *render.denoised);
}

// A render watched (python/watched_work.h): a signal, or an exception from the progress
// callback, stops it at its next safe point and is kept in `raised`, for the caller to raise
// once it has put the stopped render where it goes.
struct WatchedRender {
  RenderResult result;
  std::optional<py::error_already_set> raised;
};

// The last progress call, with the render whole: what the callback raises now is kept for
// after the render is delivered.
void report_whole(const py::object& progress_callback, WatchedRender& out) {
  if (progress_callback.is_none()) return;
  try {
    progress_callback(1.0);
  } catch (py::error_already_set& e) {
    out.raised.emplace(std::move(e));
  }
}

WatchedRender render_watched(const RenderSettings& settings, const py::object& progress_callback,
                             const std::function<RenderResult(RenderProgress&)>& run) {
  RenderProgress progress;
  progress.stop_cause = "interrupted by a signal";
  WatchedRender out;
  const std::uint64_t pixels =
      std::uint64_t(film_width(settings)) * std::uint64_t(film_height(settings));
  const auto start = std::chrono::steady_clock::now();
  const auto report = [&] {
    if (progress_callback.is_none()) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const ProgressStatus status = progress_status(settings, pixels, snapshot(progress, elapsed));
    progress_callback(status.fraction >= 0.0 ? status.fraction : 0.0);
  };
  Watched w = watch([&] { out.result = run(progress); }, progress.stop_requested, report);
  out.raised = std::move(w.raised);
  if (w.failure) {
    if (out.raised) throw std::move(*out.raised);
    std::rethrow_exception(w.failure);
  }
  if (!out.raised) report_whole(progress_callback, out);
  return out;
}

// Raises what stopped a render, with a note (Python 3.11's add_note) of where its samples are.
[[noreturn]] void raise_stopped(py::error_already_set& raised, const std::string& note) {
  const py::object value = raised.value();
  if (!note.empty() && py::hasattr(value, "add_note")) value.attr("add_note")(note);
  throw std::move(raised);
}

// A render in memory: the image, and a share of the samples where one is asked.
std::shared_ptr<Render> render_in_memory(const Scene& scene, const py::object& progress,
                                         const ParsedOptions& parsed) {
  const JobRequest& job = parsed.job;
  ResolvedRender resolved = resolve(scene, job_render_request(job));
  auto out = std::make_shared<Render>();
  if (const auto* fixed = std::get_if<FixedSamples>(&resolved.settings.samples)) {
    out->samples_asked = std::uint64_t(fixed->per_pixel);
  }
  if (!job.part.empty() || !job.sample_range.empty()) {
    if (!job.part.empty() && !job.sample_range.empty()) {
      throw InvalidInput("give " + setting("sample_range") + " or " + setting("part") +
                         ", not both");
    }
    const std::string what = job.part.empty() ? "sample_range" : "part";
    const std::uint64_t total = shareable_samples(resolved.settings, setting(what));
    restrict_to(job.part.empty() ? parse_sample_range(job.sample_range, total)
                                 : parse_part(job.part, total),
                resolved.settings);
    out->share = true;
  }
  validate(resolved.scene, resolved.settings);
  WatchedRender watched = render_watched(resolved.settings, progress, [&](RenderProgress& p) {
    return render(resolved.scene, resolved.settings, &p);
  });
  if (watched.raised) raise_stopped(*watched.raised, "");
  out->result = std::move(watched.result);
  out->scene = std::move(resolved.scene);
  out->settings = resolved.settings;
  out->stats_channels = job.request.estimate_error;
  out->passes_asked = job.request.passes.any();
  if (job.denoise && !out->share) denoise_in_memory(*out);
  return out;
}

// A render to a file, as rtiow render -o runs it: the library's session claims the output
// and its checkpoint, resumes, previews and shows it, and at the end writes the image or, for a
// render stopped short, keeps its samples.
std::shared_ptr<Render> render_to_file(const Scene& scene, const py::object& progress,
                                       const ParsedOptions& parsed) {
  check_session_options(parsed.session);
  RenderJob job = prepare_job(parsed.job, scene);
  WatchedRender watched;
  SessionEnd end;
  std::string stopped;
  {
    RenderSession session(job, parsed.job, parsed.session);
    watched = render_watched(job.settings, progress,
                             [&](RenderProgress& p) { return session.render(p); });
    const py::gil_scoped_release released;
    end = session.deliver(watched.result);
    const std::atomic<bool> stop{watched.raised.has_value()};
    session.let_viewer_finish(stop);
    if (watched.raised) {
      stopped = "rtiow: " + stopped_render_report(job, watched.result, session.checkpoint(), end);
    }
  }
  if (watched.raised) raise_stopped(*watched.raised, stopped);
  auto out = std::make_shared<Render>();
  out->samples_asked = job.samples_asked;
  out->share = job.share;
  out->written = end.written;
  out->result = std::move(watched.result);
  out->scene = std::move(job.scene);
  out->settings = job.settings;
  out->stats_channels = parsed.job.stats_channels;
  out->passes_asked = parsed.job.request.passes.any();
  out->denoised = std::move(end.denoised_image);
  return out;
}

std::shared_ptr<Render> render_scene(const Scene& scene, const py::object& progress,
                                     const py::kwargs& options) {
  const ParsedOptions parsed = parse_render_options(options);
  return parsed.job.output_given ? render_to_file(scene, progress, parsed)
                                 : render_in_memory(scene, progress, parsed);
}

// rtiow render --like: the request `image` records, each part the caller gives (a keyword, or
// the scene) replacing the image's; the recorded scene is loaded and checked to be the one the
// image was rendered from, unless the caller gives a scene.
std::shared_ptr<Render> render_like(const std::string& image, const py::object& scene,
                                    const py::object& progress, const py::kwargs& options) {
  ParsedOptions parsed = parse_render_options(options);
  const RecordedRequest recorded = read_recorded_request(image, "like image " + quote_value(image));
  parsed.job.other_inputs.push_back(image);  // read, so never the output
  std::set<RequestPart> given =
      parts_given([&](std::string_view name) { return options.contains(std::string(name)); });
  if (!scene.is_none()) given.insert(RequestPart::Scene);
  // A render in memory holds every channel; a file, what its format can.
  const ImageFormat* format = parsed.job.output_given ? image_format(parsed.job.output) : nullptr;
  const bool holds_channels = !parsed.job.output_given || (format && format->extra_channels);
  parsed.job = overlay_recorded(recorded, std::move(parsed.job), given, holds_channels,
                                parsed.session.reproducible);
  Scene chosen;
  if (scene.is_none()) {
    const py::gil_scoped_release released;
    chosen = load_job_scene(parsed.job);
    check_scene_of_image(recorded, chosen);
  } else {
    chosen = scene.cast<const Scene&>();
    parsed.job.scene_file.clear();  // not the recorded file's scene: its metadata names none
  }
  return parsed.job.output_given ? render_to_file(chosen, progress, parsed)
                                 : render_in_memory(chosen, progress, parsed);
}

// A film as an array of height x width x 3 float32 over the render's own memory.
py::array film_array(const Film& film, const std::shared_ptr<Render>& render) {
  static_assert(sizeof(Color) == 3 * sizeof(float), "a Color is three packed floats");
  const auto h = py::ssize_t(film.height()), w = py::ssize_t(film.width());
  return py::array_t<float>(
      {h, w, py::ssize_t(3)},
      {w * py::ssize_t(sizeof(Color)), py::ssize_t(sizeof(Color)), py::ssize_t(sizeof(float))},
      &film.pixels().data()->x, py::cast(render));
}

// The image: denoised where the render was.
py::array image_of(const std::shared_ptr<Render>& render) {
  return film_array(render->denoised ? render->denoised->image : render->result.film, render);
}

py::object noisy_of(const std::shared_ptr<Render>& render) {
  if (!render->denoised) return py::none();
  return film_array(render->result.film, render);
}

// The denoiser's estimate of each pixel's squared error, per channel.
py::object denoise_mse_of(const Render& render) {
  if (!render.denoised) return py::none();
  const std::vector<Vec3d>& mse = render.denoised->mse;
  py::array_t<float> out({py::ssize_t(render.result.film.height()),
                          py::ssize_t(render.result.film.width()), py::ssize_t(3)});
  float* v = out.mutable_data();
  for (std::size_t p = 0; p < mse.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) v[3 * p + c] = float(mse[p][c]);
  }
  return out;
}

py::object denoise_figures(const std::optional<DenoiseFigures>& figures) {
  if (!figures) return py::none();
  py::dict out;
  out["estimated_error"] = figures->estimated_error;
  out["noisy_error"] = figures->noisy_error;
  out["seconds"] = figures->seconds;
  return out;
}

py::array samples_of(const std::shared_ptr<Render>& render) {
  const Film& film = render->result.film;
  const auto h = py::ssize_t(film.height()), w = py::ssize_t(film.width());
  return py::array_t<std::uint32_t>({h, w}, render->result.pixel_samples.data(), py::cast(render));
}

// The variance of each pixel's mean, per channel: only where the render kept two independent
// replicates, whose spread is an honest estimate (RenderSettings::estimate_error).
py::object variance_of(const Render& render) {
  if (render.result.replicates != kReplicates) return py::none();
  const std::vector<Vec3d> variances = pixel_mean_variances(render.result);
  const auto h = py::ssize_t(render.result.film.height());
  const auto w = py::ssize_t(render.result.film.width());
  py::array_t<float> out({h, w, py::ssize_t(3)});
  float* v = out.mutable_data();
  for (std::size_t p = 0; p < variances.size(); ++p) {
    v[3 * p] = float(variances[p].x), v[3 * p + 1] = float(variances[p].y);
    v[3 * p + 2] = float(variances[p].z);
  }
  return out;
}

py::dict passes_of(const Render& render) {
  py::dict out;
  const auto h = py::ssize_t(render.result.film.height());
  const auto w = py::ssize_t(render.result.film.width());
  for (const ExtraChannel& c : pass_channels(render.result, render.settings.passes)) {
    py::array_t<float> values({h, w});
    std::copy(c.values.begin(), c.values.end(), values.mutable_data());
    out[py::str(c.name)] = values;
  }
  return out;
}

// What `--summary-json` says of a render, for a script: the command's writer's members of the
// render (core/session/render_summary.h), one shape for both.
py::dict summary_of(const Render& render) {
  const std::string json = render_members_json(
      render.scene.name, render.settings, render.result,
      render.written.empty() ? nullptr : &render.written,
      render.denoised ? std::optional(figures_of(*render.denoised)) : std::nullopt);
  return py::module_::import("json").attr("loads")(json).cast<py::dict>();
}

void write_render(const Render& render, const std::string& path, bool reproducible) {
  const py::gil_scoped_release released;
  const bool channels = render.share || render.stats_channels || render.passes_asked;
  check_image_output(path, {}, channels);
  Metadata metadata = render_metadata(render.scene, render.settings, render.result, reproducible);
  if (render.share) {  // a part file, as rtiow render --part writes it
    write_part(
        path,
        make_part(render.scene, render.settings, render.samples_asked, render.result, metadata),
        render.result.sums);
    return;
  }
  std::vector<ExtraChannel> extra =
      image_channels(render.result, render.stats_channels, render.settings.passes);
  if (!render.denoised) {
    write_image(path, render.result.film, metadata, extra, frame_placement(render.settings));
    return;
  }
  const ImageFormat* format = image_format(path);
  DenoisedOutput out =
      denoised_output(*render.denoised, format && format->extra_channels, metadata);
  if (format && format->extra_channels) {
    out.channels.insert(out.channels.end(), std::make_move_iterator(extra.begin()),
                        std::make_move_iterator(extra.end()));
  }
  write_image(path, out.image, metadata, out.channels, frame_placement(render.settings));
}

// rtiow merge: the part files added into the image one render of all their samples gives.
// Ctrl-C, or an exception from `progress`, stops the denoiser (nothing is written; the parts
// stay); the merge itself runs on. `progress(fraction)` follows the denoiser, and is called with
// 1.0 once the image is written.
std::optional<DenoiseFigures> merge_and_write(const std::vector<std::string>& parts,
                                              const std::string& output, bool stats_channels,
                                              bool denoise, int threads,
                                              const py::object& progress) {
  WorkProgress denoising;
  const bool watched = denoise && !progress.is_none();
  const auto tick = [&] {
    if (watched) progress(denoising.fraction());
  };
  std::optional<DenoiseFigures> figures = interruptible<std::optional<DenoiseFigures>>(
      [&](const std::function<bool()>& cancelled) {
        MergeRequest request;
        request.statistics = stats_channels, request.denoise = denoise, request.threads = threads;
        request.cancelled = cancelled, request.denoising = &denoising;
        return merge_to_file(parts, output, request).denoised;
      },
      tick);
  if (watched) progress(1.0);
  return figures;
}

// With `denoise`, the denoiser's figures (estimated_error, noisy_error, seconds); else None.
py::object merge_files(const std::vector<std::string>& parts, const std::string& output,
                       bool stats_channels, bool denoise, int threads, const py::object& progress) {
  return denoise_figures(
      merge_and_write(parts, output, stats_channels, denoise, threads, progress));
}

py::object denoise_files(const std::vector<std::string>& parts, const std::string& output,
                         bool stats_channels, int threads, const py::object& progress) {
  return merge_files(parts, output, stats_channels, true, threads, progress);
}

// An image to compare: a file, or a render (with its variances where it has them).
DiffInput diff_input_of(const py::handle& image) {
  if (py::isinstance<py::str>(image)) return read_diff_input(image.cast<std::string>());
  const auto render = image.cast<std::shared_ptr<Render>>();
  // A denoised image has no variances (its error is partly bias): it is compared plainly.
  if (render->denoised) return diff_input(render->denoised->image);
  DiffInput input = diff_input(render->result.film);
  if (render->result.replicates == kReplicates) {
    const std::vector<Vec3d> variances = pixel_mean_variances(render->result);
    input.variance.reserve(variances.size() * 3);
    for (const Vec3d& v : variances) {
      input.variance.insert(input.variance.end(), {float(v.x), float(v.y), float(v.z)});
    }
  }
  return input;
}

py::dict compare(const py::object& test, const py::object& reference, double alpha, int block,
                 double fail, double fail_percent) {
  const DiffInput ref = diff_input_of(reference);
  std::vector<DiffInput> tests;
  if (py::isinstance<py::list>(test) || py::isinstance<py::tuple>(test)) {
    for (const py::handle& t : test) tests.push_back(diff_input_of(t));
  } else {
    tests.push_back(diff_input_of(test));
  }
  if (tests.empty()) throw InvalidInput("diff: no test image");
  ComparisonSettings settings;
  settings.alpha = alpha, settings.block = block;
  PlainThresholds& t = settings.thresholds;
  t.fail = fail, t.fail_percent = fail_percent, t.warn = fail, t.warn_percent = fail_percent;
  const ImageComparison c = compare_images(ref, tests, settings);
  py::dict out;
  out["mode"] = c.mode;
  if (c.noise) {
    out["worst_block_z"] = c.noise->worst_block_z, out["failing_blocks"] = c.noise->failing_blocks;
    out["image_z"] = c.noise->image_z;
  } else {
    out["max_error"] = c.plain->max_error, out["rms_error"] = c.plain->rms_error;
    out["fail_percent"] = c.plain->fail_percent;
  }
  out["verdict"] = to_string(c.verdict);
  out["passed"] = c.verdict != DiffVerdict::Fail;
  out["description"] = c.description;
  return out;
}

// A scene from a dict in the scene file's words (docs/scene-format.md), as Mitsuba's load_dict
// takes one: written as JSON (numpy arrays as lists) and read by the scene file's reader, so it
// gets every check a file gets, each error naming its place ("/spheres/3/radius").
Scene scene_from_dict(const py::dict& description) {
  const py::module_ json = py::module_::import("json");
  const py::object as_list =
      py::module_::import("builtins")
          .attr("eval")(
              "lambda o: o.tolist() if hasattr(o, 'tolist') else "
              "(_ for _ in ()).throw(TypeError(f'{type(o).__name__} is not a JSON value'))");
  std::string text;
  try {
    text =
        json.attr("dumps")(description, py::arg("allow_nan") = false, py::arg("default") = as_list)
            .cast<std::string>();
  } catch (py::error_already_set& e) {
    throw InvalidInput("scene dict: " + std::string(py::str(e.value())));
  }
  return parse_scene(text, "scene dict");
}

py::dict scene_to_dict(const Scene& scene) {
  return py::module_::import("json").attr("loads")(scene_to_json(scene));
}

// Every channel of an image file, by name: height x width float32 each.
py::dict read_channels(const std::string& path) {
  ImageChannels in;
  {
    const py::gil_scoped_release released;
    in = read_image_channels(path, "image " + quote_value(path), 1);
  }
  py::dict out;
  const auto h = py::ssize_t(in.height), w = py::ssize_t(in.width);
  for (std::size_t c = 0; c < in.names.size(); ++c) {
    py::array_t<float> values({h, w});
    const std::vector<float> plane = in.plane(c);
    std::copy(plane.begin(), plane.end(), values.mutable_data());
    out[py::str(in.names[c])] = values;
  }
  return out;
}

py::array read_image(const std::string& path) {
  DiffInput input = read_diff_input(path);
  py::array_t<float> out({py::ssize_t(input.height), py::ssize_t(input.width), py::ssize_t(3)});
  std::copy(input.rgb.begin(), input.rgb.end(), out.mutable_data());
  return out;
}

// Scenes: built in, from files, from dicts.
void bind_scenes(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A scene: spheres, their materials, a camera and a sky.")
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def_property_readonly(
          "spheres", [](const Scene& s) { return s.spheres.size(); }, "How many spheres it holds.")
      .def("to_dict", &scene_to_dict,
           "The scene in the scene file's words (docs/scene-format.md), as a dict: "
           "rtiow.scene(d) gives it back, and json.dump(d, f) writes a scene file.")
      .def("__repr__", [](const Scene& s) {
        return "<rtiow.Scene '" + s.name + "', " + std::to_string(s.spheres.size()) + " spheres>";
      });

  m.def(
      "builtin_scene",
      [](const std::string& name, std::uint64_t scene_seed) {
        return make_builtin_scene(name, scene_seed);
      },
      py::arg("name") = "cover", py::arg("scene_seed") = kDefaultSceneSeed,
      "A built-in scene (see builtin_scenes()); scene_seed lays out the random ones.");
  m.def(
      "builtin_scenes",
      [] {
        std::vector<std::string> names;
        for (const auto& s : builtin_scenes()) names.push_back(s.name);
        return names;
      },
      "The built-in scenes' names.");
  m.def(
      "load_scene", [](const std::string& path) { return load_scene_file(path); }, py::arg("path"),
      "A scene file (JSON, docs/scene-format.md).");
  m.def("scene", &scene_from_dict, py::arg("description"),
        "A scene built in Python: a dict in the scene file's words (docs/scene-format.md: "
        "camera, image, background, materials, spheres), checked as a file is.");
}

// A render and what it gives.
void bind_renders(py::module_& m) {
  py::class_<Render, std::shared_ptr<Render>>(
      m, "Render",
      "A finished render: its image and sample counts as numpy arrays, and its summary.")
      .def_property_readonly("image", &image_of,
                             "The image: height x width x 3 float32, linear (no copy).")
      .def_property_readonly("spp", &samples_of,
                             "Each pixel's sample count: height x width uint32 (no copy).")
      .def_property_readonly(
          "variance", [](const Render& r) { return variance_of(r); },
          "The variance of each pixel's mean (height x width x 3), where the render kept two "
          "replicates (stats_channels, the error targets, the independent sampler); else None.")
      .def_property_readonly(
          "passes", [](const Render& r) { return passes_of(r); },
          "The first-hit passes asked (passes=...), by channel name: height x width float32.")
      .def_property_readonly("noisy", &noisy_of,
                             "With denoise=True, the noisy image the denoiser started from "
                             "(height x width x 3 float32, no copy); else None.")
      .def_property_readonly(
          "denoise_mse", [](const Render& r) { return denoise_mse_of(r); },
          "With denoise=True, the denoiser's estimate of each pixel's squared error, bias "
          "included (height x width x 3); else None.")
      .def_property_readonly(
          "summary", [](const Render& r) { return summary_of(r); },
          "What --summary-json says of the render.")
      .def("write", &write_render, py::arg("path"), py::arg("reproducible") = false,
           "Writes the image (and its channels) with rtiow's metadata, as rtiow render -o does.");

  m.def("render_like", &render_like, py::arg("image"), py::kw_only(), py::arg("scene") = py::none(),
        py::arg("progress") = py::none(),
        "Renders again what `image` (a file rtiow wrote) records: its scene, size, samples, "
        "seed, camera, ..., as rtiow render --like does. Each keyword of render() given, and "
        "scene=, replaces its part of the recorded request; the recorded scene must still be "
        "the one the image was rendered from.");
  m.def("render", &render_scene, py::arg("scene"), py::kw_only(), py::arg("progress") = py::none(),
        "Renders `scene`. Keyword arguments are rtiow render's long options with underscores "
        "(width, height, spp, seed, sampler, depth, time_limit, image_error, target_error, "
        "adaptive, min_spp, passes, crop, stats_channels, roulette, threads, accel, lookfrom, "
        "lookat, vup, vfov, aperture, focus_distance, fresnel, part, sample_range). With "
        "output=PATH it renders to that file as rtiow render -o does: a checkpoint beside it "
        "(checkpoint=seconds, 0: none), resume=True to continue one, restart=True to discard "
        "it, keep_state=True to keep it for a later refinement, preview=seconds, "
        "display='host:port' (tev), reproducible=True. progress(fraction) is called about every "
        "50 ms. Ctrl-C stops the render and raises KeyboardInterrupt; to a file, the samples "
        "are kept in the checkpoint and the exception's note says how to continue.");
}

// Images: compared, merged from parts, read.
void bind_images(py::module_& m) {
  m.def("diff", &compare, py::arg("test"), py::arg("reference"), py::kw_only(),
        py::arg("alpha") = 0.01, py::arg("block") = 16, py::arg("fail") = 1e-6,
        py::arg("fail_percent") = 0.0,
        "Compares a test image (a path or a Render; a list of renders with other seeds) with a "
        "reference, as rtiow diff does: noise-aware where both have variances, by seeds for a "
        "list, else plain. Returns a dict with 'passed', 'verdict' and the figures.");
  m.def("merge", &merge_files, py::arg("parts"), py::arg("output"), py::kw_only(),
        py::arg("stats_channels") = false, py::arg("denoise") = false, py::arg("threads") = 0,
        py::arg("progress") = py::none(),
        "Adds part files (renders with part= or sample_range=, written) into the image one "
        "render of all their samples gives, as rtiow merge does; checks they belong together. "
        "With denoise=True the image is denoised and its figures returned, as by denoise(), "
        "progress(fraction) following the denoiser. threads: 0 for every core.");
  m.def("denoise", &denoise_files, py::arg("parts"), py::arg("output"), py::kw_only(),
        py::arg("stats_channels") = false, py::arg("threads") = 0, py::arg("progress") = py::none(),
        "Denoises a render kept as part files (render(..., denoise=True, part='0/1', "
        "output=...)), as rtiow denoise does. Returns the denoised image's estimated error "
        "(relative RMS, offset 0.01), the noisy image's and the denoiser's seconds. "
        "progress(fraction) is called about every 50 ms with the share of the denoising done, "
        "and with 1.0 once the image is written; what it raises stops the denoiser (nothing "
        "is written) and is raised. threads: 0 for every core.");
  m.def("read_image", &read_image, py::arg("path"),
        "An image file's R, G, B as height x width x 3 float32 (linear files as stored).");
  m.def("read_channels", &read_channels, py::arg("path"),
        "Every channel of an image file by name (R, G, B, spp, variance.R, albedo.R, ...): "
        "height x width float32 each.");
}
}  // namespace
}  // namespace rtiow::python

PYBIND11_MODULE(_rtiow, m) {
  using namespace rtiow;
  using namespace rtiow::python;
  m.doc() = "rtiow: a path tracer for the scenes of Ray Tracing in One Weekend";
  // rtiow's one-line refusals are ValueErrors; every other failure is a RuntimeError.
  py::register_exception<InvalidInput>(m, "InvalidInput", PyExc_ValueError).attr("__doc__") =
      "rtiow's one-line refusal of an input (a bad option, a scene file, an "
      "image): a ValueError.";

  bind_scenes(m);
  bind_renders(m);
  bind_images(m);
  m.attr("__version__") = rtiow::version();
}

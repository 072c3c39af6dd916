// The files a render writes: the library's image and the command line's alike, metadata, the
// summary for scripts, every format, --like from each, byte-identical files.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/rtiow.h"
#include "core/session/progress_status.h"
#include "tests/cli_helpers.h"

namespace {

using namespace rtiow::test::cli;

TEST(Cli, TheLibraryAndTheCommandLineGiveOneRequestTheSameImage) {
  struct Case {
    std::string options;
    std::string scene;
    rtiow::RenderRequest request;
  };
  rtiow::RenderRequest camera;
  camera.height = 30, camera.spp = 4, camera.max_depth = 8;
  camera.camera.lookfrom = rtiow::Vec3d{-2, 2, 1}, camera.camera.vfov_degrees = 40;
  camera.fresnel = rtiow::FresnelModel::Exact;
  rtiow::RenderRequest error_driven;
  error_driven.width = 40, error_driven.image_error = 0.2;
  rtiow::RenderRequest uniform;
  uniform.width = 24, uniform.spp = 3, uniform.seed = 7;
  uniform.sampler = rtiow::SamplerKind::Independent;
  const std::vector<Case> cases = {
      {"--scene materials --height 30 --spp 4 --depth 8 --lookfrom -2,2,1 --vfov 40 "
       "--fresnel exact",
       "materials", camera},
      {"--scene cover --width 40 --image-error 0.2", "cover", error_driven},
      {"--scene defocus --width 24 --spp 3 --seed 7 --sampler independent", "defocus", uniform},
  };
  for (const Case& c : cases) {
    const fs::path out = output_path(c.scene + ".exr");
    const CommandResult r = run_rtiow("render -q " + c.options + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    int width = 0, height = 0;
    const std::vector<float> cli = exr_pixels(out, width, height);

    const rtiow::ResolvedRender job =
        rtiow::resolve(rtiow::make_builtin_scene(c.scene, 1), c.request);
    const rtiow::Film film = rtiow::render(job.scene, job.settings).film;
    ASSERT_EQ(film.width(), width) << c.options;
    ASSERT_EQ(film.height(), height) << c.options;
    ASSERT_EQ(cli.size(), film.pixels().size() * 3);
    EXPECT_EQ(std::memcmp(cli.data(), film.pixels().data(), cli.size() * sizeof(float)), 0)
        << c.options;
  }
}

// A library render with RenderSettings{} takes every setting a scene file makes, as `rtiow
// render FILE` does (issue 70: it rendered a file's "depth": 12 at 50). Each case changes one
// field of a small file; the library's image equals the command's, and differs from the base
// file's, so the field reached both.
TEST(Cli, TheLibrarysDefaultsAreTheSceneFilesInEveryField) {
  const auto scene_file = [](const std::string& image, const std::string& camera,
                             const std::string& sky, const std::string& red) {
    return R"({"version": 1, "name": "fields", "image": )" + image + R"(, "camera": )" + camera +
           R"(, "background": )" + sky + R"(, "materials": {
             "ground": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
             "red": {"type": "lambertian", "albedo": )" +
           red + R"(},
             "steel": {"type": "metal", "albedo": [0.8, 0.8, 0.8], "fuzz": 0.2}},
           "spheres": [{"center": [0, -100.5, -1], "radius": 100, "material": "ground"},
                       {"center": [0, 0, -1], "radius": 0.5, "material": "red"},
                       {"center": [1, 0, -1], "radius": 0.5, "material": "steel"}]})";
  };
  const std::string image = R"({"width": 24, "aspect_ratio": 2, "spp": 3, "depth": 6})";
  const std::string camera = R"({"lookfrom": [0, 0.5, 1.5], "lookat": [0, 0, -1], "vfov": 50})";
  const std::string sky = R"({"horizon": [1, 1, 1], "zenith": [0.3, 0.5, 1]})";
  const std::string red = "[0.7, 0.2, 0.2]";
  struct Case {
    std::string field, text;
  };
  const std::vector<Case> cases = {
      {"base", scene_file(image, camera, sky, red)},
      {"size", scene_file(R"({"width": 20, "aspect_ratio": 1.25, "spp": 3, "depth": 6})", camera,
                          sky, red)},
      {"spp",
       scene_file(R"({"width": 24, "aspect_ratio": 2, "spp": 5, "depth": 6})", camera, sky, red)},
      {"depth",
       scene_file(R"({"width": 24, "aspect_ratio": 2, "spp": 3, "depth": 2})", camera, sky, red)},
      {"camera", scene_file(image, R"({"lookfrom": [0.5, 1, 2], "lookat": [0, 0, -1], "vfov": 35,
                                       "aperture": 0.1, "focus_distance": 3})",
                            sky, red)},
      {"sky", scene_file(image, camera,
                         R"({"horizon": [0.9, 0.6, 0.4], "zenith": [0.1, 0.1, 0.4]})", red)},
      {"materials", scene_file(image, camera, sky, "[0.2, 0.7, 0.2]")},
  };
  std::vector<float> base;
  for (const Case& c : cases) {
    const fs::path file = output_path(c.field + ".json");
    std::ofstream(file) << c.text;
    const fs::path out = output_path(c.field + ".exr");
    const CommandResult r = run_rtiow("render -q " + file.string() + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << c.field << ": " << r.stderr_text;
    int width = 0, height = 0;
    const std::vector<float> cli = exr_pixels(out, width, height);

    const rtiow::RenderResult library =
        rtiow::render(rtiow::load_scene_file(file.string()), rtiow::RenderSettings{});
    ASSERT_EQ(library.film.width(), width) << c.field;
    ASSERT_EQ(library.film.height(), height) << c.field;
    ASSERT_EQ(cli.size(), library.film.pixels().size() * 3) << c.field;
    EXPECT_EQ(std::memcmp(cli.data(), library.film.pixels().data(), cli.size() * sizeof(float)), 0)
        << c.field << ": the library's RenderSettings{} and rtiow render differ";
    if (c.field == "base") {
      base = cli;
      EXPECT_EQ(width, 24);
      EXPECT_EQ(height, 12);
    } else {
      EXPECT_NE(cli, base) << c.field << " changed nothing: the case does not test the field";
    }
  }
}

// bench-point times the render command's own loop: with the command's sampler and roulette it
// traces exactly the rays `render --seed 0` traces, and each option reaches the loop.
TEST(Cli, BenchPointTracesTheRenderCommandsRays) {
  const std::string job = " --scene cover --width 40 --height 23 --spp 4 --depth 50";
  std::set<std::int64_t> counts;
  for (const char* sampler : {"independent", "sobol"}) {
    for (const char* roulette : {"on", "off"}) {
      const std::string options = job + " --sampler " + sampler + " --roulette " + roulette;
      const CommandResult point = run_rtiow("bench-point --repeat 1" + options);
      ASSERT_EQ(point.exit_code, 0) << point.stderr_text;
      const auto figures = nlohmann::json::parse(point.stdout_text);
      EXPECT_EQ(figures["sampler"], sampler);

      const fs::path out = output_path("cli_bench_point.exr");
      const CommandResult r =
          run_rtiow("render --seed 0 -q --checkpoint 0" + options + " -o " + out.string());
      ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
      auto in = OIIO::ImageInput::open(out.string());
      ASSERT_TRUE(in);
      const std::int64_t rays = in->spec().get_int_attribute("rtiow:rays_traced");
      EXPECT_EQ(figures["rays"].get<std::int64_t>(), rays) << options;
      counts.insert(rays);
    }
  }
  EXPECT_EQ(counts.size(), 4u) << "each sampler and roulette traces its own paths";
}

TEST(Cli, WritesTheImageWithMetadataAndSaysWhere) {
  const fs::path out = output_path("cli_materials.exr");
  const CommandResult r = run_rtiow(
      "render --scene materials --width 32 --spp 2 --depth 5 --seed 9 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(out.string()), std::string::npos) << "summary names the file";
  EXPECT_NE(r.stderr_text.find("Mrays/s"), std::string::npos);

  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.width, 32);
  EXPECT_EQ(spec.height, 18);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp"), 2);
  EXPECT_EQ(spec.get_int_attribute("rtiow:depth"), 5);
  EXPECT_EQ(spec.get_int_attribute("rtiow:seed"), 9);
  EXPECT_EQ(spec.get_string_attribute("rtiow:scene"), "materials");
  EXPECT_EQ(spec.get_string_attribute("rtiow:accelerator"), "embree");
  EXPECT_GT(spec.get_int_attribute("rtiow:rays_traced"), 0);
  EXPECT_GT(spec.get_float_attribute("rtiow:render_seconds"), 0.0f);
}

// --summary-json: the summary a script reads says what the image's own metadata says.
TEST(Cli, TheSummaryForScriptsAgreesWithTheImage) {
  const fs::path out = output_path("summary.exr"), summary = output_path("summary.json");
  CommandResult r = run_rtiow("render -q --scene materials --width 32 --height 18 --spp 3 -o " +
                              out.string() + " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto j = nlohmann::json::parse(slurp(summary));
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(summary_schema_violations({summary}), "");
  EXPECT_EQ(j["schema"], 2);
  EXPECT_EQ(j["command"], "render");
  EXPECT_EQ(j["version"], std::string(spec.get_string_attribute("rtiow:version")));
  EXPECT_EQ(j["output"], out.string());
  EXPECT_EQ(j["scene"], "materials");
  EXPECT_EQ(j["width"], 32);
  EXPECT_EQ(j["height"], 18);
  EXPECT_EQ(j["accelerator"], std::string(spec.get_string_attribute("rtiow:accelerator")));
  EXPECT_EQ(j["sampler"], std::string(spec.get_string_attribute("rtiow:sampler")));
  EXPECT_EQ(j["rays"], spec.get_int_attribute("rtiow:rays_traced"));
  EXPECT_EQ(j["spp"]["least"], 3);
  EXPECT_EQ(j["spp"]["most"], 3);
  EXPECT_TRUE(j["stopped"].is_null());
  EXPECT_EQ(j["seed"], 1);
  EXPECT_EQ(j["spp"]["asked"], 3);
  // Every render estimates its error: one Sobol sequence gives a bound, as the image records.
  EXPECT_TRUE(j["error"]["target"].is_null());
  EXPECT_EQ(j["error"]["estimate"], "upper bound");
  EXPECT_EQ(j["error"]["estimate"], std::string(spec.get_string_attribute("rtiow:error_estimate")));
  EXPECT_NEAR(j["error"]["estimated"].get<double>(),
              spec.get_float_attribute("rtiow:estimated_image_error"), 1e-6);
  EXPECT_EQ(j["exit_code"], 0);
  // The whole command's time, of which the sample loop is a part.
  EXPECT_GE(j["seconds"].get<double>(), j["render_seconds"].get<double>());
  EXPECT_GT(j["threads"].get<int>(), 0);
  EXPECT_GT(j["mrays_per_second"].get<double>(), 0.0);
  // An error target: the goal asked and the estimate reached, as the image records it.
  r = run_rtiow("render -q --width 48 --height 32 --image-error 0.05 -o " + out.string() +
                " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  j = nlohmann::json::parse(slurp(summary));
  in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(summary_schema_violations({summary}), "");
  EXPECT_EQ(j["error"]["target"]["kind"], "image");
  EXPECT_EQ(j["error"]["target"]["asked"], 0.05);
  EXPECT_EQ(j["error"]["estimate"], "calibrated");
  EXPECT_NEAR(j["error"]["estimated"].get<double>(),
              in->spec().get_float_attribute("rtiow:estimated_image_error"), 1e-6);
  EXPECT_EQ(j["error"]["target"]["reached"], j["error"]["estimated"].get<double>() <= 0.05);
  EXPECT_LE(j["spp"]["least"].get<int>(), j["spp"]["most"].get<int>());
  // Stopped by a signal: said, with the command's exit code and the samples the image holds.
  const fs::path stopped = output_path("stopped.exr");
  BackgroundRender render({"render", "-q", "--width", "300", "--spp", "100000", "--checkpoint", "0",
                           "-o", stopped.string(), "--summary-json", summary.string()});
  ASSERT_TRUE(render.wait_until_rendering());
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  render.signal(SIGTERM);
  ASSERT_EQ(render.wait(30.0), 128 + SIGTERM) << render.stderr_text();
  j = nlohmann::json::parse(slurp(summary));
  in = OIIO::ImageInput::open(stopped.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(summary_schema_violations({summary}), "");
  EXPECT_EQ(j["stopped"], "interrupted by a signal");
  EXPECT_EQ(j["exit_code"], 128 + SIGTERM);
  EXPECT_EQ(j["spp"]["least"], in->spec().get_int_attribute("rtiow:spp"));
  // The summary is an output like the image: never the image itself.
  r = run_rtiow("render -q --width 16 --spp 1 -o " + out.string() + " --summary-json " +
                out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("another output of this command"), std::string::npos)
      << r.stderr_text;
}

// diff --summary-json: the verdict and figures a script reads are those the command printed
// and exited with.
// An output named in another encoding than UTF-8, which JSON cannot hold: the image is written
// and the summary names it with U+FFFD for the stray byte (it ended in nlohmann-json's
// exception, exit 1, with the image written).
TEST(Cli, TheSummaryNamesAnOutputWhoseNameIsNotUtf8) {
  const fs::path out = output_path("latin1-\xe9.png"), summary = output_path("latin1.json");
  const CommandResult r = run_rtiow("render -q --scene materials --width 16 --spp 1 -o " +
                                    out.string() + " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(fs::exists(out));
  const auto j = nlohmann::json::parse(slurp(summary));
  const std::string named = j["output"];
  EXPECT_NE(named.find("latin1-\xef\xbf\xbd.png"), std::string::npos) << named;
}

TEST(Cli, TheDiffSummaryForScriptsIsTheVerdictPrinted) {
  const fs::path a = output_path("a.exr"), b = output_path("b.exr"), c = output_path("c.exr");
  const fs::path summary = output_path("diff.json");
  for (const auto& [path, args] :
       {std::pair{a, std::string("--seed 1")}, std::pair{b, std::string("--seed 2")},
        std::pair{c, std::string("--seed 1 --depth 1")}}) {
    ASSERT_EQ(run_rtiow("render -q --width 48 --height 32 --spp 16 --stats-channels " + args +
                        " -o " + path.string())
                  .exit_code,
              0);
  }
  CommandResult r =
      run_rtiow("diff " + a.string() + " " + b.string() + " --summary-json " + summary.string());
  auto j = nlohmann::json::parse(slurp(summary));
  EXPECT_EQ(summary_schema_violations({summary}), "");
  EXPECT_EQ(j["schema"], 2);
  EXPECT_EQ(j["command"], "diff");
  EXPECT_EQ(j["mode"], "noise");
  EXPECT_EQ(j["exit_code"], r.exit_code);
  EXPECT_NE(r.stdout_text.find(j["verdict"].get<std::string>()), std::string::npos);
  EXPECT_EQ(j["noise"]["blocks"], 6);
  EXPECT_TRUE(j["plain"].is_null());
  // A real change, compared plainly: a failure, with the figures printed.
  r = run_rtiow("diff --mode plain " + a.string() + " " + c.string() + " --summary-json " +
                summary.string());
  j = nlohmann::json::parse(slurp(summary));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(j["verdict"], "FAILURE");
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_GT(j["plain"]["max_error"].get<double>(), 0.0);
  EXPECT_TRUE(j["plain"]["thresholds"]["hardfail"].is_null());
  EXPECT_TRUE(j["noise"].is_null());
  EXPECT_EQ(summary_schema_violations({summary}), "");
  // No verdict (images of other sizes: 3; a file diff cannot read: 4): a summary all the same,
  // saying why (issue 70: a script found no file for these exits).
  const fs::path small = output_path("small.exr");
  ASSERT_EQ(run_rtiow("render -q --width 24 --height 16 --spp 2 -o " + small.string()).exit_code,
            0);
  for (const auto& [other, code] :
       {std::pair{small.string(), 3}, std::pair{output_path("none.exr").string(), 4}}) {
    SCOPED_TRACE(other);
    fs::remove(summary);
    r = run_rtiow("diff " + a.string() + " " + other + " --summary-json " + summary.string());
    EXPECT_EQ(r.exit_code, code) << r.stderr_text;
    ASSERT_TRUE(fs::exists(summary)) << r.stderr_text;
    j = nlohmann::json::parse(slurp(summary));
    EXPECT_EQ(j["verdict"], "could not compare");
    EXPECT_EQ(j["exit_code"], code);
    EXPECT_NE(r.stderr_text.find(j["failure"].get<std::string>()), std::string::npos)
        << r.stderr_text;
    EXPECT_TRUE(j["width"].is_null());
    EXPECT_TRUE(j["plain"].is_null() && j["noise"].is_null());
    EXPECT_EQ(summary_schema_violations({summary}), "");
  }
}

TEST(Cli, EveryAdvertisedFormatIsWritten) {
  for (const char* ext : {".png", ".exr", ".ppm", ".jpg", ".tif"}) {
    const fs::path out = output_path(std::string("format") + ext);
    const CommandResult r =
        run_rtiow("render -q --scene wide-angle --width 16 --spp 1 -o " + out.string());
    EXPECT_EQ(r.exit_code, 0) << ext << ": " << r.stderr_text;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in) << ext;
    EXPECT_EQ(in->spec().width, 16) << ext;
  }
}

// Every format that can hold text carries the whole request, read back through OpenImageIO as
// any program would: PNG and EXR as "rtiow:<key>" attributes, JPEG and TIFF as one JSON object
// in the image description. HDR, PPM, BMP and TGA carry none of it (docs/usage.md), and no
// made-up "Software" either (TGA's used to read back as "rtiow 204.7").
TEST(Cli, EveryFormatThatHoldsTextCarriesTheWholeRequest) {
  const fs::path scene = output_path("edited.json");
  ASSERT_EQ(run_rtiow("scene materials -o " + scene.string()).exit_code, 0);
  const std::vector<std::string> keys = {
      "rtiow:scene",   "rtiow:scene_file", "rtiow:scene_digest", "rtiow:camera",
      "rtiow:fresnel", "rtiow:sampler",    "rtiow:seed",         "rtiow:spp",
      "rtiow:depth",   "rtiow:version",    "rtiow:accelerator",  "rtiow:russian_roulette"};
  for (const char* ext :
       {".png", ".exr", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".ppm", ".bmp", ".tga"}) {
    SCOPED_TRACE(ext);
    const fs::path out = output_path(std::string("provenance") + ext);
    const CommandResult r =
        run_rtiow("render -q " + scene.string() +
                  " --width 16 --spp 2 --seed 5 --vfov 60 --fresnel exact -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    const std::string e = ext;
    if (e == ".png" || e == ".exr") {
      for (const std::string& key : keys) EXPECT_NE(spec.find_attribute(key), nullptr) << key;
      EXPECT_EQ(spec.get_string_attribute("rtiow:scene_file"), scene.string());
      EXPECT_EQ(spec.get_string_attribute("rtiow:fresnel"), "exact");
      EXPECT_NE(spec.get_string_attribute("rtiow:camera").find(" vfov 60 "), std::string::npos);
    } else if (e == ".jpg" || e == ".jpeg" || e == ".tif" || e == ".tiff") {
      const auto all = nlohmann::json::parse(spec.get_string_attribute("ImageDescription"));
      for (const std::string& key : keys) EXPECT_TRUE(all.contains(key)) << key;
      EXPECT_EQ(all["rtiow:seed"], 5);
      EXPECT_EQ(all["rtiow:fresnel"], "exact");
      EXPECT_EQ(all["rtiow:version"].get<std::string>(),
                std::string(spec.get_string_attribute("Software")).substr(6));
    } else {
      EXPECT_EQ(spec.find_attribute("Software"), nullptr);
      EXPECT_EQ(spec.get_string_attribute("ImageDescription"), "");
    }
  }
}

// The gallery of docs/ is what this build renders: each picture, rendered again from its own
// metadata, gives its bytes. `cmake --build build --target gallery` renders them all again
// (cmake/Gallery.cmake).
TEST(Cli, TheGalleryIsWhatThisBuildRenders) {
  const fs::path gallery = fs::path(RTIOW_SOURCE_DIR) / "docs" / "gallery";
  int pictures = 0;
  for (const auto& entry : fs::directory_iterator(gallery)) {
    if (entry.path().extension() != ".png") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++pictures;
    const fs::path again = output_path("gallery-" + entry.path().filename().string());
    fs::remove(again);
    const CommandResult r =
        run_rtiow("render -q --like " + entry.path().string() + " -o " + again.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_TRUE(slurp(entry.path()) == slurp(again))
        << "docs/gallery is stale: cmake --build build --target gallery renders it again";
  }
  EXPECT_EQ(pictures, 6);
}

// --like renders an image again from its own metadata: the same bytes, from every format that
// holds the request, with settings away from every default (an override of the camera, a
// sampler, a seed, exact Fresnel, an error target with its cap and minimum, no roulette).
TEST(Cli, LikeRendersTheSameFileAgainFromEveryFormatThatHoldsTheRequest) {
  const fs::path scene = output_path("like-scene.json");
  ASSERT_EQ(run_rtiow("scene materials -o " + scene.string()).exit_code, 0);
  const std::string settings =
      " --width 24 --height 20 --seed 9 --sampler padded-sobol --depth 7 --vfov 60 "
      "--lookfrom 0.5,1,2 --fresnel exact --reproducible ";
  struct Case {
    const char* ext;
    std::string sampling;
  };
  for (const Case& c : {Case{".png", "--spp 3"}, Case{".jpg", "--spp 2 --scene-seed 4"},
                        Case{".png", "--spp 3 --roulette off"},
                        Case{".tif", "--image-error 0.2 --spp 40 --min-spp 3"},
                        Case{".exr", "--target-error 0.07 --spp 30 --min-spp 5 --stats-channels"},
                        Case{".exr", "--adaptive --spp 20"},
                        Case{".exr", "--adaptive --spp 20 --stats-channels"}}) {
    SCOPED_TRACE(std::string(c.ext) + " " + c.sampling);
    const fs::path first = output_path(std::string("like-first") + c.ext);
    const fs::path again = output_path(std::string("like-again") + c.ext);
    fs::remove(first), fs::remove(again);
    CommandResult r =
        run_rtiow("render -q " + scene.string() + settings + c.sampling + " -o " + first.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    r = run_rtiow("render -q --like " + first.string() + " -o " + again.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const std::string a = slurp(first), b = slurp(again);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "the file rendered --like differs from the original";
  }
}

// An option given with --like replaces its part of the recorded request, and only that.
TEST(Cli, LikeTakesEachOptionGivenOverTheImages) {
  const fs::path first = output_path("like-base.exr"), again = output_path("like-changed.exr");
  fs::remove(first), fs::remove(again);
  ASSERT_EQ(run_rtiow("render -q --scene spheres:30 --scene-seed 6 --width 20 --spp 3 --seed 11 "
                      "--aperture 0.2 -o " +
                      first.string())
                .exit_code,
            0);
  const CommandResult r = run_rtiow("render -q --like " + first.string() +
                                    " --spp 2 --aperture 0 -o " + again.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto in = OIIO::ImageInput::open(again.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.width, 20);
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp"), 2);
  EXPECT_EQ(spec.get_int_attribute("rtiow:seed"), 11);
  EXPECT_EQ(spec.get_int_attribute("rtiow:scene_seed"), 6);
  EXPECT_EQ(spec.get_string_attribute("rtiow:scene"), "spheres:30");
  const std::string camera = spec.get_string_attribute("rtiow:camera");
  EXPECT_NE(camera.find(" aperture 0 "), std::string::npos) << camera;
}

// The camera record is in the scene file's words; an image of rtiow 0.3.0 spelt it as the
// render command's options, and renders again to the same bytes.
TEST(Cli, LikeReadsTheCameraOfAnOlderImage) {
  const fs::path base = output_path("like-camera-base.png"), older = output_path("like-older.png");
  const fs::path a = output_path("like-camera-a.png"), b = output_path("like-camera-b.png");
  ASSERT_EQ(run_rtiow("render -q --reproducible --scene cover --width 24 --spp 2 --vfov 31.5 -o " +
                      base.string())
                .exit_code,
            0);
  OIIO::ImageBuf buffer(base.string());
  ASSERT_TRUE(buffer.read());
  std::string record = buffer.spec().get_string_attribute("rtiow:camera");
  EXPECT_EQ(record.rfind("lookfrom 13,2,3 lookat 0,0,0 vup 0,1,0 vfov 31.5 aperture 0.1 ", 0), 0u)
      << record;
  std::string spelt;  // "--lookfrom 13,2,3 ... --focus-dist 10"
  std::istringstream words(record);
  for (std::string name, value; words >> name >> value;) {
    spelt += (spelt.empty() ? "--" : " --") +
             (name == "focus_distance" ? std::string("focus-dist") : name) + " " + value;
  }
  buffer.specmod().attribute("rtiow:camera", spelt);
  ASSERT_TRUE(buffer.write(older.string()));
  ASSERT_EQ(run_rtiow("render -q --like " + base.string() + " -o " + a.string()).exit_code, 0);
  const CommandResult r = run_rtiow("render -q --like " + older.string() + " -o " + b.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(a), slurp(b)) << spelt;
  EXPECT_EQ(slurp(a), slurp(base));
  for (const fs::path& p : {base, older, a, b}) fs::remove(p);
}

// What --like cannot repeat is refused in one line, before any work: a scene file edited since
// the image (until the scene is given again), an image with no request, an adaptive render a
// clock stopped (until the sampling is given), and an output that would replace the image.
TEST(Cli, LikeRefusesWhatItCannotRenderAgain) {
  const fs::path scene = output_path("like-edited.json"), image = output_path("like-edited.png");
  const fs::path out = output_path("like-out.png");
  ASSERT_EQ(run_rtiow("scene materials -o " + scene.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render -q " + scene.string() + " --width 16 --spp 2 -o " + image.string())
                .exit_code,
            0);
  std::string text = slurp(scene);
  const std::string ground = "\"radius\":100.0";
  ASSERT_NE(text.find(ground), std::string::npos);
  text.replace(text.find(ground), ground.size(), "\"radius\":101.0");  // a bigger ground
  { std::ofstream(scene, std::ios::binary) << text; }
  CommandResult r = run_rtiow("render -q --like " + image.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("changed since"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(out));
  r = run_rtiow("render -q --like " + image.string() + " " + scene.string() + " -o " +
                out.string());
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;

  const fs::path hdr = output_path("like.hdr");
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 16 --spp 1 -o " + hdr.string()).exit_code,
            0);
  r = run_rtiow("render -q --like " + hdr.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("holds no rtiow provenance"), std::string::npos) << r.stderr_text;

  const fs::path timed = output_path("like-timed.png");
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 16 --adaptive --time-limit 0.1 -o " +
                      timed.string())
                .exit_code,
            0);
  r = run_rtiow("render -q --like " + timed.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("time limit"), std::string::npos) << r.stderr_text;
  r = run_rtiow("render -q --like " + timed.string() + " --spp 2 -o " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;

  r = run_rtiow("render -q --like " + image.string() + " -o " + image.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("input"), std::string::npos) << r.stderr_text;

  // A scene file the image names relative to where it was rendered, from elsewhere: the name
  // is said to be the image's, and the scene given again renders it.
  const fs::path elsewhere = fs::path(RTIOW_TEST_OUTPUT_DIR) / "like-relative-dir";
  fs::remove_all(elsewhere);
  fs::create_directories(elsewhere);
  fs::copy_file(scene, elsewhere / "edited.json");
  ASSERT_EQ(
      run_rtiow("render -q edited.json --width 16 --spp 1 -o relative.png", elsewhere.string())
          .exit_code,
      0);
  fs::remove(out);
  r = run_rtiow("render -q --like " + (elsewhere / "relative.png").string() + " -o " +
                out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("rendered from scene file 'edited.json', a name relative to the "
                               "directory that render ran in"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(out));
  r = run_rtiow("render -q --like " + (elsewhere / "relative.png").string() + " " +
                (elsewhere / "edited.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  fs::remove(out);

  // Metadata edited into what no option takes: refused as the image's, exit 2.
  const fs::path base = output_path("like-hostile-base.png");
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 16 --spp 1 -o " + base.string()).exit_code,
            0);
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"rtiow:spp", "ten"},
                                                        {"rtiow:sampler", "bogus"},
                                                        {"rtiow:camera", "--lookfrom nan,1,1"},
                                                        {"rtiow:camera", "--lookfrom 1,2"},
                                                        {"rtiow:camera", "lookfrom 1,2,3,4"},
                                                        {"rtiow:camera", "vfov 20 vfov 30"},
                                                        {"rtiow:camera", "vfov"},
                                                        {"rtiow:camera", "zoom 2"},
                                                        {"rtiow:crop", "0,0,5,5"},
                                                        {"rtiow:frame", "16x9"},
                                                        {"rtiow:passes", "albedo,sparkle"}}) {
    SCOPED_TRACE(key + "=" + value);
    const fs::path edited = output_path("like-hostile.png");
    OIIO::ImageBuf buffer(base.string());
    ASSERT_TRUE(buffer.read());
    buffer.specmod().attribute(key, value);
    ASSERT_TRUE(buffer.write(edited.string()));
    r = run_rtiow("render -q --like " + edited.string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("--like image"), std::string::npos) << r.stderr_text;
  }
}

TEST(Cli, ReproducibleFilesAreByteIdenticalAcrossThreadCounts) {
  const fs::path one = output_path("threads1.png"), two = output_path("threads2.png");
  const std::string common = "render -q --reproducible --scene cover --width 40 --spp 3 ";
  ASSERT_EQ(run_rtiow(common + "--threads 1 -o " + one.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(common + "--threads 2 -o " + two.string()).exit_code, 0);
  const std::string a = slurp(one), b = slurp(two);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b) << "files differ between 1 and 2 threads";
}

// EXR and TIFF writers stamp the time of writing unless told otherwise: a file that carried it
// would differ from the same job's file written a second later.
TEST(Cli, FilesCarryNoWallClockDate) {
  const std::string common = "render -q --reproducible --scene cover --width 16 --spp 2 ";
  for (const std::string name : {"dated.exr", "dated.tif", "dated-part.exr"}) {
    const fs::path path = output_path(name);
    const std::string part = name == "dated-part.exr" ? "--part 0/2 " : "";
    ASSERT_EQ(run_rtiow(common + part + "-o " + path.string()).exit_code, 0) << name;
    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in) << name;
    const OIIO::ParamValue* date = in->spec().find_attribute("DateTime");
    EXPECT_TRUE(date == nullptr || date->get_string().empty())
        << name << " carries DateTime " << date->get_string();
  }
}

}  // namespace

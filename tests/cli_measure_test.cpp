// Measurements and adaptive renders from the command line: bench and accuracy, their
// summaries, statistics channels, budgets and error targets, sphere fields.

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

TEST(Cli, BenchWritesFiguresAndPlot) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "bench-out";
  fs::remove_all(dir);
  const fs::path json_path = dir / "bench.json", plot = dir / "bench.png";
  const CommandResult r = run_rtiow(
      "bench --width 32 --height 18 --spp 1 --depth 4 --scaling-width 24 --scaling-height 14 "
      "--scaling-spp 1 --scaling-depth 3 --max-spheres 100 --repeat 1 --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("embree / naive"), std::string::npos) << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("embree traversal alone"), std::string::npos);
  const std::string figures = slurp(json_path);
  // The ratios, or, where this tiny run's timings made one impossible (a loaded machine can),
  // each failed measurement in its place: which of the two depends on the clock, not the code.
  const auto failed_measurements = nlohmann::json::parse(figures)["cover"]["failed_measurements"];
  if (failed_measurements.empty()) {
    EXPECT_NE(r.stdout_text.find("render / raw trace rate"), std::string::npos) << r.stdout_text;
  } else {
    for (const auto& f : failed_measurements)
      EXPECT_NE(r.stdout_text.find("failed measurement: " + f.get<std::string>()),
                std::string::npos)
          << r.stdout_text;
  }
  for (const char* key : {"\"cover\"", "\"scaling\"", "\"trace\"", "\"traversal\"",
                          "\"embree_1_thread\"", "\"peak_rss_mb\"", "\"build_seconds\""}) {
    EXPECT_NE(figures.find(key), std::string::npos) << key;
  }
  EXPECT_TRUE(fs::exists(plot)) << r.stdout_text;

  // An instrument (issue 70): every figure after a warm-up, with its runs and their spread, the
  // sampler and seed of every row, the machine and build, and every run in a CSV.
  const auto bench = nlohmann::json::parse(figures);
  EXPECT_EQ(bench["context"]["rtiow"], rtiow::version());
  const std::string version_text = run_rtiow("--version").stdout_text;
  EXPECT_NE(version_text.find("\ncommit: " + bench["context"]["commit"].get<std::string>() + "\n"),
            std::string::npos)
      << version_text;
  EXPECT_EQ(bench["context"]["build"].size(), rtiow::build_facts().size());
  EXPECT_FALSE(bench["context"]["cpu"].get<std::string>().empty());
  EXPECT_EQ(bench["cover"]["sampler"], "independent");
  EXPECT_EQ(bench["cover"]["seed"], 0);
  int csv_rows_expected = 0;
  const auto check_spread = [&](const nlohmann::json& f, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_LE(f["mrays_per_second_min"].get<double>(), f["mrays_per_second"].get<double>());
    EXPECT_LE(f["mrays_per_second"].get<double>(), f["mrays_per_second_max"].get<double>());
    // The median absolute deviation: at most half the range, and 0 exactly for one run.
    const double mad = f["mrays_per_second_mad"].get<double>();
    EXPECT_GE(mad, 0.0);
    EXPECT_LE(mad,
              f["mrays_per_second_max"].get<double>() - f["mrays_per_second_min"].get<double>());
    if (f["runs"] == 1) {
      EXPECT_EQ(mad, 0.0);
    }
    EXPECT_EQ(f["each_run"].size(), f["runs"].get<std::size_t>());
    csv_rows_expected += int(f["each_run"].size());
  };
  for (const char* key : {"embree", "naive", "embree_1_thread", "trace", "traversal"}) {
    check_spread(bench["cover"][key], key);
  }
  for (const char* key : {"embree", "naive", "embree_1_thread"}) {
    EXPECT_GT(bench["cover"][key]["warmup_seconds"].get<double>(), 0.0) << key;
    EXPECT_EQ(bench["cover"][key]["sampler"], "independent") << key;
  }
  for (const auto& point : bench["scaling"]) {
    for (const char* key : {"embree", "naive"}) {
      if (point.contains(key)) check_spread(point[key], point["n"].dump() + " " + key);
    }
  }
  const std::string csv = slurp(dir / "bench.csv");
  EXPECT_EQ(csv.rfind("section,configuration,spheres,", 0), 0u) << csv;
  EXPECT_EQ(count_lines(csv), 1 + csv_rows_expected) << csv;
  EXPECT_NE(csv.find("\ncover,naive,485,32,18,1,4,"), std::string::npos) << csv;
  EXPECT_NE(r.stdout_text.find("machine: "), std::string::npos) << r.stdout_text;

  // docs/performance.md shows a run of the program: each line this run prints has a line of
  // that form there (numbers, paths and alignment aside), and each line there but the ones of
  // a naive loop over its time budget is printed here.
  const auto form = [](const std::string& line) {
    return std::regex_replace(
        output_form(std::regex_replace(line, std::regex(R"(^(figures|runs|plot|machine): .*)"),
                                       "$1: PATH")),
        std::regex(" +"), " ");
  };
  const std::string docs = slurp(fs::path(RTIOW_SOURCE_DIR) / "docs" / "performance.md");
  const std::size_t begin = docs.find("$ build/bin/rtiow bench");
  ASSERT_NE(begin, std::string::npos) << "docs/performance.md shows no run of rtiow bench";
  std::set<std::string> shown, printed;
  {
    std::istringstream in(docs.substr(begin, docs.find("```", begin) - begin));
    std::string line;
    std::getline(in, line);  // the command
    while (std::getline(in, line)) {
      if (!line.empty() && line.find("skipped") == std::string::npos &&
          line.find("naive stopped") == std::string::npos) {
        shown.insert(form(line));
      }
    }
  }
  // A run this small on a busy machine may fail a measurement: it then prints why instead of
  // the ratios, which the docs' run shows (a timing is never asserted).
  const bool failed = r.stdout_text.find("failed measurement: ") != std::string::npos;
  std::istringstream out(r.stdout_text);
  for (std::string line; std::getline(out, line);) {
    if (!line.empty() && line.find("failed measurement: ") == std::string::npos) {
      printed.insert(form(line));
    }
  }
  if (failed) {
    for (auto it = shown.begin(); it != shown.end();) {
      const bool ratio = it->find("render / ") != std::string::npos ||
                         it->find("thread scaling") != std::string::npos;
      it = ratio ? shown.erase(it) : std::next(it);
    }
  }
  for (const std::string& line : printed) {
    EXPECT_TRUE(shown.count(line)) << "docs/performance.md has no line like: " << line;
  }
  for (const std::string& line : shown) {
    EXPECT_TRUE(printed.count(line)) << "rtiow bench prints no line like: " << line;
  }
}

// bench --compare: two bench.json files figure by figure, a difference beyond the noise only
// where the runs' ranges are apart, none judged from one run (issue 70).
TEST(Cli, BenchComparesTwoFiguresFilesByTheirRuns) {
  const fs::path a = output_path("a-bench.json"), b = output_path("b-bench.json");
  const auto rate = [](double median, double least, double most, int runs) {
    return nlohmann::json{{"mrays_per_second", median},
                          {"mrays_per_second_min", least},
                          {"mrays_per_second_max", most},
                          {"runs", runs}};
  };
  nlohmann::json first = {{"context", {{"cpu", "CPU A"}, {"rtiow", "0.3.0"}}},
                          {"cover",
                           {{"embree", rate(10, 9.5, 10.5, 3)},
                            {"naive", rate(2, 1.9, 2.1, 3)},
                            {"trace", rate(14, 13, 15, 3)}}},
                          {"scaling", {{{"n", 10}, {"embree", rate(12, 11, 13, 3)}}}}};
  nlohmann::json second = first;
  second["context"]["cpu"] = "CPU B";
  second["cover"]["embree"] = rate(12, 11.8, 12.4, 3);    // apart: faster
  second["cover"]["naive"] = rate(2.05, 1.95, 2.2, 3);    // overlapping
  second["cover"]["trace"] = rate(20, 20, 20, 1);         // one run: no range
  second["scaling"][0]["embree"] = rate(6, 5.5, 6.5, 3);  // apart: slower
  std::ofstream(a) << first.dump();
  std::ofstream(b) << second.dump();
  const CommandResult r = run_rtiow("bench --compare " + a.string() + " " + b.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const std::string& out = r.stdout_text;
  EXPECT_NE(out.find("(CPU A, rtiow 0.3.0)"), std::string::npos) << out;
  EXPECT_NE(out.find("(CPU B, rtiow 0.3.0)"), std::string::npos) << out;
  const auto row = [&](const std::string& label) {
    const std::size_t at = out.find("  " + label + " ");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  EXPECT_NE(row("cover, embree").find("1.200x  faster, beyond the noise"), std::string::npos)
      << out;
  EXPECT_NE(row("cover, naive").find("within the noise"), std::string::npos) << out;
  EXPECT_NE(row("cover, raw rtcIntersect1").find("no ranges to judge by"), std::string::npos)
      << out;
  EXPECT_NE(row("spheres:10, embree").find("0.500x  slower, beyond the noise"), std::string::npos)
      << out;
  EXPECT_NE(out.find("2 figures differ beyond the noise"), std::string::npos) << out;
  const fs::path other = output_path("other.json");
  std::ofstream(other) << R"({"figures": []})";
  const CommandResult refused = run_rtiow("bench --compare " + a.string() + " " + other.string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(count_lines(refused.stderr_text), 1) << refused.stderr_text;
  EXPECT_NE(refused.stderr_text.find("other.json': not a bench.json (rtiow bench --out DIR writes "
                                     "one)"),
            std::string::npos)
      << refused.stderr_text;
  // Read as every JSON input is: a nesting no bench.json has is refused, not followed.
  std::ofstream(other) << std::string(200000, '[') << std::string(200000, ']');
  const CommandResult deep = run_rtiow("bench --compare " + other.string() + " " + a.string());
  EXPECT_EQ(deep.exit_code, 2);
  EXPECT_EQ(count_lines(deep.stderr_text), 1) << deep.stderr_text;
  EXPECT_NE(deep.stderr_text.find("not a bench.json"), std::string::npos) << deep.stderr_text;
}

// --quick gives bench and accuracy the settings of a short run, but for the options given.
TEST(Cli, QuickRunsTakeTheirOwnSettingsButTheOptionsGiven) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "quick-runs";
  fs::remove_all(dir);
  CommandResult r = run_rtiow("bench --quick --max-spheres 100 --out " + (dir / "b").string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto bench = nlohmann::json::parse(slurp(dir / "b" / "bench.json"));
  EXPECT_EQ(bench["cover"]["width"], 200);
  EXPECT_EQ(bench["repeat"], 1);
  EXPECT_EQ(bench["scaling"].size(), 2u);  // 10 and 100 spheres: --max-spheres is the user's
  // A cache named in another encoding than UTF-8: accuracy.json names it with U+FFFD for the
  // stray byte (it ended in nlohmann-json's exception, the figures unwritten).
  r = run_rtiow("accuracy -q --quick --width 48 --out " + (dir / "a").string() + " --cache-dir " +
                (dir / "cache\xff").string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto accuracy = nlohmann::json::parse(slurp(dir / "a" / "accuracy.json"));
  EXPECT_EQ(accuracy["reference_path"].get<std::string>().rfind((dir / "cache\uFFFD/").string(), 0),
            0u)
      << accuracy["reference_path"];
  EXPECT_EQ(accuracy["width"], 48);
  EXPECT_EQ(accuracy["max_spp"], 256);
  EXPECT_EQ(accuracy["reference_spp"], 1024);
  EXPECT_EQ(accuracy["repeat"], 1);
  // The denoised curve: 2 to 256 spp, each with the error the denoiser reported, its time in
  // the row's, and a lower error at each doubling of the samples.
  const auto& denoised = accuracy["denoised"];
  ASSERT_EQ(denoised.size(), 8u) << denoised.dump();
  EXPECT_EQ(accuracy["denoised_sampler"], "sobol");
  for (std::size_t i = 0; i < denoised.size(); ++i) {
    EXPECT_GT(denoised[i]["estimated_error"].get<double>(), 0.0);
    EXPECT_GE(denoised[i]["seconds"].get<double>(), denoised[i]["denoise_seconds"].get<double>());
    if (i > 0) {
      EXPECT_LT(denoised[i]["rel_mse"].get<double>(), denoised[i - 1]["rel_mse"].get<double>());
    }
  }
}

// bench and accuracy --summary-json: the shared head, and headline figures that are the ones
// the full figures hold; a summary path that cannot be written is refused before the work.
TEST(Cli, MeasurementsWriteSummariesInTheSharedSchema) {
  const fs::path dir = empty_output_dir("measure-summaries");
  const fs::path bench_summary = dir / "bench-summary.json";
  CommandResult r = run_rtiow("bench --quick --max-spheres 100 --out " + (dir / "b").string() +
                              " --summary-json " + bench_summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto figures = nlohmann::json::parse(slurp(dir / "b" / "bench.json"));
  const auto bench = nlohmann::json::parse(slurp(bench_summary));
  EXPECT_EQ(summary_schema_violations({bench_summary}), "");
  EXPECT_EQ(bench["schema"], 2);
  EXPECT_EQ(bench["command"], "bench");
  EXPECT_EQ(bench["exit_code"], 0);
  EXPECT_EQ(bench["version"], rtiow::version());
  EXPECT_EQ(bench["files"]["figures"], (dir / "b" / "bench.json").string());
  EXPECT_EQ(bench["cover"]["embree_mrays_per_second"],
            figures["cover"]["embree"]["mrays_per_second"]);
  EXPECT_DOUBLE_EQ(bench["cover"]["thread_scaling"].get<double>(),
                   figures["cover"]["embree"]["mrays_per_second"].get<double>() /
                       figures["cover"]["embree_1_thread"]["mrays_per_second"].get<double>());
  ASSERT_EQ(bench["scaling"].size(), figures["scaling"].size());
  EXPECT_EQ(bench["scaling"][1]["spheres"], 100);
  EXPECT_GT(bench["seconds"].get<double>(), 0.0);
  // A warning is in the summary exactly when the command printed it.
  EXPECT_EQ(bench["warnings"].empty(), r.stderr_text.find("warning:") == std::string::npos)
      << r.stderr_text;

  const fs::path accuracy_summary = dir / "accuracy-summary.json";
  r = run_rtiow("accuracy -q --quick --width 32 --out " + (dir / "a").string() + " --cache-dir " +
                (dir / "cache").string() + " --summary-json " + accuracy_summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto measured = nlohmann::json::parse(slurp(dir / "a" / "accuracy.json"));
  const auto accuracy = nlohmann::json::parse(slurp(accuracy_summary));
  EXPECT_EQ(summary_schema_violations({accuracy_summary}), "");
  EXPECT_EQ(accuracy["schema"], 2);
  EXPECT_GT(accuracy["threads"].get<int>(), 0);
  EXPECT_EQ(accuracy["command"], "accuracy");
  EXPECT_EQ(accuracy["width"], 32);
  EXPECT_EQ(accuracy["reference"]["spp"], 1024);
  EXPECT_EQ(accuracy["files"]["csv"], (dir / "a" / "accuracy.csv").string());
  EXPECT_EQ(accuracy["book_quality"], measured["summary"]["book_quality"]);
  ASSERT_EQ(accuracy["image_error"].size(), measured["image_error"].size());
  EXPECT_EQ(accuracy["image_error"][0]["asked"], measured["image_error"][0]["parameter"]);

  // Refused before the work: nothing measured, no directory made.
  r = run_rtiow("bench --quick --out " + (dir / "never").string() + " --summary-json " +
                (dir / "no-such-dir" / "s.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("--summary-json"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(dir / "never"));
}

TEST(Cli, AdaptiveRenderWritesStatisticsChannelsAndItsSampleCounts) {
  const fs::path out = output_path("adaptive.exr");
  const CommandResult r = run_rtiow(
      "render --scene cover --width 32 --target-error 0.2 --spp 256 "
      "--min-spp 8 --sampler sobol --stats-channels -o " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("target error 0.2"), std::string::npos) << r.stderr_text;
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.nchannels, 7);
  EXPECT_EQ(spec.channelnames[3], "spp");
  EXPECT_EQ(spec.channelnames[6], "variance.B");
  EXPECT_EQ(spec.get_string_attribute("rtiow:sampler"), "sobol");
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp_min"), 8);
  const int most = spec.get_int_attribute("rtiow:spp_max");
  EXPECT_GT(most, 8);
  EXPECT_LE(most, 256);
  // The metadata's counts are the spp channel's.
  std::vector<float> pixels(std::size_t(spec.width * spec.height * 7));
  ASSERT_TRUE(in->read_image(0, 0, 0, 7, OIIO::TypeDesc::FLOAT, pixels.data()));
  double total = 0, largest = 0, smallest = 1e9;
  for (std::size_t p = 0; p < pixels.size(); p += 7) {
    total += pixels[p + 3];
    largest = std::max(largest, double(pixels[p + 3]));
    smallest = std::min(smallest, double(pixels[p + 3]));
    EXPECT_GE(pixels[p + 4], 0.0f);
  }
  EXPECT_EQ(largest, most);
  EXPECT_EQ(smallest, 8);
  EXPECT_NEAR(total / double(spec.width * spec.height), spec.get_float_attribute("rtiow:spp_mean"),
              1e-3);
}

// --adaptive's --spp is a budget: the file says so, and the pixels' counts spread around it.
TEST(Cli, BudgetRenderRecordsItsBudgetAndSpreadsItsSamples) {
  const fs::path out = output_path("budget.exr");
  const CommandResult r =
      run_rtiow("render --scene cover --width 32 --spp 64 --adaptive -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("adaptive)"), std::string::npos) << r.stderr_text;
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  EXPECT_EQ(spec.get_string_attribute("rtiow:adaptive"), "sqrt(variance/cost)");
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp_budget"), 64);
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp_min"), 16);
  EXPECT_GT(spec.get_int_attribute("rtiow:spp_max"), 64) << "the noisiest pixels get more";
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp_limit"), 1 << 24);
}

// An error-driven render that stops at its --spp cap says that it did not reach its target,
// and how far it got, in the summary and in the file.
TEST(Cli, ErrorTargetsMissedAtTheCapAreReported) {
  const fs::path out = output_path("capped.exr");
  const CommandResult image =
      run_rtiow("render --scene cover --width 32 --spp 16 --image-error 0.001 -o " + out.string());
  ASSERT_EQ(image.exit_code, 0) << image.stderr_text;
  EXPECT_NE(image.stderr_text.find("image error 0.001 not reached"), std::string::npos)
      << image.stderr_text;
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_GT(in->spec().get_float_attribute("rtiow:estimated_image_error"), 0.001f);
  in.reset();
  const CommandResult pixels =
      run_rtiow("render --scene cover --width 32 --spp 32 --target-error 0.001 -o " + out.string());
  ASSERT_EQ(pixels.exit_code, 0) << pixels.stderr_text;
  EXPECT_NE(pixels.stderr_text.find("target error 0.001 not reached by"), std::string::npos)
      << pixels.stderr_text;
  in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_GT(in->spec().get_int_attribute("rtiow:pixels_above_target"), 0);
  in.reset();
  // Ended by its time limit far from the target: not reached, on the line and in the summary,
  // with the estimate it got to (or none, on a machine too loaded to judge a round in time) and
  // the samples it took, not the cap's.
  const fs::path summary = output_path("capped.json");
  const CommandResult timed = run_rtiow(
      "render --scene cover --width 64 --spp 4096 --image-error 0.0005 --time-limit 1 -o " +
      out.string() + " --summary-json " + summary.string());
  ASSERT_EQ(timed.exit_code, 0) << timed.stderr_text;
  EXPECT_NE(timed.stderr_text.find("image error 0.0005 not reached: "), std::string::npos)
      << timed.stderr_text;
  EXPECT_EQ(timed.stderr_text.find("at 4096 spp"), std::string::npos) << timed.stderr_text;
  const auto j = nlohmann::json::parse(slurp(summary));
  EXPECT_EQ(summary_schema_violations({summary}), "");
  EXPECT_EQ(j["error"]["target"]["reached"], false);
  const double estimated = j["error"]["estimated"].get<double>();
  if (estimated == 0.0) {
    EXPECT_NE(timed.stderr_text.find("no estimate yet"), std::string::npos) << timed.stderr_text;
  } else {
    EXPECT_GT(estimated, 0.0005);
  }
  // Reached: no such words.
  const CommandResult reached =
      run_rtiow("render --scene cover --width 32 --spp 4096 --image-error 0.1 -o " + out.string());
  ASSERT_EQ(reached.exit_code, 0) << reached.stderr_text;
  EXPECT_EQ(reached.stderr_text.find("not reached"), std::string::npos) << reached.stderr_text;
}

TEST(Cli, RefusesAdaptiveAndStatisticsOptionsWhereTheyCannotWork) {
  expect_refused("--scene cover --width 8 --spp 4 --sampler halton", "--sampler");
  expect_refused("--scene cover --width 8 --spp 4 --stats-channels", "must be .exr");
  expect_refused("--scene cover --width 8 --spp 4 --target-error -1", "--target-error");
  expect_refused("--scene cover --width 8 --spp 4 --target-error 0.1 --min-spp 1", "--min-spp");
  expect_refused("--scene cover --width 8 --spp 4 --image-error nan", "--image-error");
  expect_refused("--scene cover --width 8 --spp 4 --adaptive --image-error 0.1",
                 "choose one adaptive mode");
  // A budget at or below the minimum would silently render uniformly.
  expect_refused("--scene cover --width 8 --spp 16 --adaptive", "leaves nothing to allocate");
  const fs::path part = output_path("part.exr");
  const CommandResult r = run_rtiow(
      "render -q --scene cover --width 8 --spp 4 --target-error 0.1 "
      "--part 0/2 -o " +
      part.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--target-error"), std::string::npos) << r.stderr_text;
  const CommandResult budget = run_rtiow(
      "render -q --scene cover --width 8 --spp 64 --adaptive --part 0/2 -o " + part.string());
  EXPECT_EQ(budget.exit_code, 2);
  EXPECT_NE(budget.stderr_text.find("--adaptive needs all of a pixel's samples"), std::string::npos)
      << budget.stderr_text;
  EXPECT_FALSE(fs::exists(part));
}

TEST(Cli, AccuracyMeasuresWritesFiguresAndReusesItsReference) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + "-accuracy");
  fs::remove_all(dir);  // a previous run's reference must not be reused
  const std::string args =
      "accuracy -q --width 16 --reference-spp 256 --max-spp 64 "
      "--fixed-spp 4 --depths 1,2,50 --target-errors 0.3 --image-errors 0.3 --repeat 1 --out " +
      dir.string() + " --cache-dir " + (dir / "cache").string();
  const CommandResult first = run_rtiow(args);
  ASSERT_EQ(first.exit_code, 0) << first.stderr_text << first.stdout_text;
  EXPECT_NE(first.stdout_text.find("RMSE slope"), std::string::npos) << first.stdout_text;
  EXPECT_NE(first.stdout_text.find("bit-identical to embree"), std::string::npos);
  EXPECT_EQ(first.stdout_text.find("reused from the cache"), std::string::npos);
  const std::string figures = slurp(dir / "accuracy.json");
  for (const char* key :
       {"\"rmse_slope\"", "\"equal_time_factor\"", "\"budget_equal_time_factor\"",
        "\"book_quality\"", "\"padded-sobol\"", "\"image_error\"", "\"depth_sweep\"", "\"fresnel\"",
        "\"adaptive\"", "\"intersector\"", "\"denoised_equal_time_factor\""}) {
    EXPECT_NE(figures.find(key), std::string::npos) << key;
  }
  const std::string csv = slurp(dir / "accuracy.csv");
  EXPECT_EQ(csv.rfind("group,choice,parameter", 0), 0u) << csv;
  // Header, 3 samplers x spp 1..64, 3 x budgets 32 and 64, the book's estimator at spp
  // 1..64, one image error, 3 depths, two intersectors, two Fresnel models, one target error,
  // denoised at spp 2..64.
  EXPECT_EQ(count_lines(csv), 1 + 3 * 7 + 3 * 2 + 7 + 1 + 3 + 2 + 2 + 1 + 6) << csv;
  EXPECT_NE(csv.find("\ndenoised,sobol --denoise,64.0,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nbook,independent without roulette,64.0,"), std::string::npos) << csv;
  EXPECT_NE(first.stdout_text.find("time to the book's quality"), std::string::npos);
  EXPECT_NE(first.stdout_text.find("without Russian roulette"), std::string::npos);
  EXPECT_NE(first.stdout_text.find("fewer rays"), std::string::npos) << first.stdout_text;
  EXPECT_NE(figures.find("\"ray_factor\""), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "accuracy.png")) << first.stdout_text;

  const CommandResult second = run_rtiow(args);
  ASSERT_EQ(second.exit_code, 0) << second.stderr_text;
  EXPECT_NE(second.stdout_text.find("reused from the cache"), std::string::npos);
  // Other settings: a new reference, not the cached one.
  const CommandResult other = run_rtiow(args + " --scene-seed 2");
  ASSERT_EQ(other.exit_code, 0) << other.stderr_text;
  EXPECT_EQ(other.stdout_text.find("reused from the cache"), std::string::npos);

  const CommandResult refused =
      run_rtiow("accuracy -q --reference-spp 128 --max-spp 64 --out " + dir.string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.stderr_text.find("--reference-spp"), std::string::npos);
  // Every broken sample-count limit in the one line, not one per attempt.
  const CommandResult all =
      run_rtiow("accuracy -q --reference-spp 8 --max-spp 4 --book-spp 2 --out " + dir.string());
  EXPECT_EQ(all.exit_code, 2);
  for (const char* option : {"--max-spp must be >= 64", "--reference-spp must be at least 4x",
                             "--book-spp must be >= 16"}) {
    EXPECT_NE(all.stderr_text.find(option), std::string::npos) << all.stderr_text;
  }
}

// A cache directory that cannot be made is refused before the reference is rendered, in
// rtiow's words (it rendered for seconds, then printed a raw filesystem error; issue 70).
TEST(Cli, AccuracyRefusesAnUnusableCacheBeforeRendering) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + "-accuracy");
  fs::remove_all(dir);
  const CommandResult r = run_rtiow(
      "accuracy --width 16 --reference-spp 256 --max-spp 64 --fixed-spp 4 --depths 1 "
      "--repeat 1 --out " +
      dir.string() + " --cache-dir /proc/rtiow-no-such-cache");
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("rtiow: error: --cache-dir '/proc/rtiow-no-such-cache': cannot "
                               "keep the reference there: "),
            std::string::npos)
      << r.stderr_text;
  EXPECT_EQ(r.stderr_text.find("rendering the reference"), std::string::npos) << r.stderr_text;
  EXPECT_EQ(r.stderr_text.find("filesystem error"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(dir / "accuracy.json"));
  // The default cache, under an unusable HOME: named as the default, not as an option the user
  // never gave.
  const CommandResult by_default = run_rtiow(
      "accuracy --width 16 --reference-spp 256 --max-spp 64 --fixed-spp 4 --depths 1 "
      "--repeat 1 --out " +
          dir.string(),
      "", {"HOME=/proc/rtiow-no-such-home", "XDG_CACHE_HOME="});
  EXPECT_EQ(by_default.exit_code, 2) << by_default.stderr_text;
  EXPECT_NE(by_default.stderr_text.find(
                "rtiow: error: the default reference cache '/proc/rtiow-no-such-home/.cache/rtiow' "
                "cannot keep the reference: "),
            std::string::npos)
      << by_default.stderr_text;
  EXPECT_NE(by_default.stderr_text.find("give --cache-dir DIR"), std::string::npos);
  EXPECT_EQ(by_default.stderr_text.find("rendering the reference"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "accuracy.json"));
}

TEST(Cli, SphereFieldScenesRenderAndRefuseBadCounts) {
  const fs::path out = output_path("field.png");
  EXPECT_EQ(
      run_rtiow("render -q --scene spheres:1000 --width 24 --spp 1 -o " + out.string()).exit_code,
      0);
  EXPECT_TRUE(fs::exists(out));
  expect_refused("--scene spheres:0", "N must be a whole number");
  expect_refused("--scene spheres:12x", "N must be a whole number");
  // An unknown name lists the generated scenes too.
  expect_refused("--scene nope", "spheres:N with N from 1 to 100000000");
}

}  // namespace

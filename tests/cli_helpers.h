#pragma once
// What the command-line tests share (tests/cli_*_test.cpp): rtiow started with an argument
// vector (tests/launch.h), each test's own output names, a refusal checked as a user meets it,
// and the images the command line wrote read back.

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

#include "core/session/progress_status.h"
#include "core/rtiow.h"
#include "tests/background_render.h"
#include "tests/launch.h"
#include "tests/test_files.h"

namespace rtiow::test::cli {

namespace fs = std::filesystem;

using rtiow::test::BackgroundRender;

struct CommandResult {
  int exit_code;
  std::string stdout_text;
  std::string stderr_text;
};

using rtiow::test::slurp;

// CTest runs the tests in parallel processes: each test gets its own files.
inline std::string test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// rtiow with `args` (split at spaces, no shell), in `directory` (empty: the tests' own), with
// `environment` ("NAME=value") added and standard input from `input`.
inline CommandResult run_rtiow(const std::string& args, const std::string& directory = "",
                               const std::vector<std::string>& environment = {},
                               const std::string& input = "/dev/null") {
  const fs::path dir = RTIOW_TEST_OUTPUT_DIR;
  const fs::path out = dir / (test_name() + ".stdout"), err = dir / (test_name() + ".stderr");
  rtiow::test::Launch command;
  command.argv = rtiow::test::words(args);
  command.argv.insert(command.argv.begin(), RTIOW_BINARY);
  command.directory = directory, command.environment = environment;
  command.stdin_path = input;
  command.stdout_path = out.string(), command.stderr_path = err.string();
  const int code = rtiow::test::launch(command);
  return {code, slurp(out), slurp(err)};
}

// The violations of docs/summary.schema.json (the published --summary-json schema) in these
// summaries, one line each, as Python's jsonschema finds them: empty when they hold to it.
inline std::string summary_schema_violations(const std::vector<fs::path>& summaries) {
  const fs::path source = RTIOW_SOURCE_DIR;
  const fs::path report = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + ".schema");
  rtiow::test::Launch check;
  check.argv = {"python3", (source / "tests/schema/check_summary.py").string(),
                (source / "docs/summary.schema.json").string()};
  for (const fs::path& s : summaries) check.argv.push_back(s.string());
  check.stdout_path = report.string(), check.stderr_path = report.string();
  const int code = rtiow::test::launch(check);
  const std::string found = slurp(report);
  return code == 0 ? "" : found.empty() ? "the schema check exited " + std::to_string(code) : found;
}

inline fs::path output_path(const std::string& name) {
  const fs::path p = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + "-" + name);
  fs::remove(p);
  return p;
}

// A directory of the test's outputs, `name` under the output directory, made empty.
inline fs::path empty_output_dir(const std::string& name) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline int count_lines(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '\n'));
}

inline void expect_refused(const std::string& args, const std::string& needle) {
  const fs::path out = output_path("refused.png");
  const CommandResult r = run_rtiow("render -q -o " + out.string() + " " + args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.stderr_text;
  EXPECT_EQ(count_lines(r.stderr_text), 1) << "one-line error expected: " << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(out)) << "a refused render wrote " << out;
}

// A line of program output with what varies between runs taken out: every number becomes N
// and the path after "->" or "wrote ... to" becomes PATH (the docs show another machine's).
inline std::string output_form(const std::string& line) {
  static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e[+-]?[0-9]+)?)");
  static const std::regex path(R"((-> |to )\S+)");
  return std::regex_replace(std::regex_replace(line, path, "$1PATH"), number, "N");
}

// The pixels of an .exr the command line wrote.
inline std::vector<float> exr_pixels(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  width = in->spec().width, height = in->spec().height;
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data());
  return rgb;
}

// Channel `name` of an EXR, one float a pixel; empty when the file or the channel is missing.
inline std::vector<float> exr_channel(const fs::path& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const int c = in->spec().channelindex(name);
  if (c < 0) return {};
  std::vector<float> values(std::size_t(in->spec().width) * std::size_t(in->spec().height));
  in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, values.data());
  return values;
}

}  // namespace rtiow::test::cli

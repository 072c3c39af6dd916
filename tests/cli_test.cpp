// The rtiow executable as a user meets it: exit codes, one-line errors, no file written
// on refusal, the file and its metadata on success.

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

#include "app/progress_status.h"
#include "core/rtiow.h"
#include "tests/background_render.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;

using rtiow::test::BackgroundRender;

struct CommandResult {
  int exit_code;
  std::string stdout_text;
  std::string stderr_text;
};

using rtiow::test::slurp;

// CTest runs the tests of this file in parallel processes: each test gets its own files.
std::string test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// `environment`: "NAME=value " assignments put before the command.
CommandResult run_rtiow(const std::string& args, const std::string& environment = "") {
  const fs::path dir = RTIOW_TEST_OUTPUT_DIR;
  const fs::path out = dir / (test_name() + ".stdout"), err = dir / (test_name() + ".stderr");
  const std::string command = environment + std::string(RTIOW_BINARY) + " " + args + " > " +
                              out.string() + " 2> " + err.string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

fs::path output_path(const std::string& name) {
  const fs::path p = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + "-" + name);
  fs::remove(p);
  return p;
}

// A directory of the test's outputs, `name` under the output directory, made empty.
fs::path empty_output_dir(const std::string& name) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int count_lines(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '\n'));
}

void expect_refused(const std::string& args, const std::string& needle) {
  const fs::path out = output_path("refused.png");
  const CommandResult r = run_rtiow("render -q -o " + out.string() + " " + args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.stderr_text;
  EXPECT_EQ(count_lines(r.stderr_text), 1) << "one-line error expected: " << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(out)) << "a refused render wrote " << out;
}

TEST(Cli, HelpIsAvailableAndTrue) {
  const CommandResult top = run_rtiow("--help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.stdout_text.find("render"), std::string::npos);
  const CommandResult render = run_rtiow("render --help");
  EXPECT_EQ(render.exit_code, 0);
  for (const char* option : {"--scene", "--output", "--width", "--height", "--spp", "--depth",
                             "--seed", "--threads", "--quiet", "--accel", "--list-scenes"}) {
    EXPECT_NE(render.stdout_text.find(option), std::string::npos) << option;
  }
}

// Every command's help shows a value's kind or its choices, not CLI11's parser strings
// ("--seed UINT:NUMBER >= 0=1", "--alpha FLOAT:NUMBER >= 0:FLOAT in [1e-12 - 0.5]=0.01"), and
// every option of every command, the hidden bench-point's too, says what it is for.
TEST(Cli, HelpShowsKindsAndDescriptionsNotParserStrings) {
  for (const char* command :
       {"render", "scene", "merge", "bench", "bench-point", "accuracy", "diff"}) {
    const CommandResult help = run_rtiow(std::string(command) + " --help");
    EXPECT_EQ(help.exit_code, 0) << command;
    for (const char* parser_text : {"NUMBER >=", "FLOAT in [", "INT in [", "TEXT:{"}) {
      EXPECT_EQ(help.stdout_text.find(parser_text), std::string::npos)
          << command << " --help shows " << parser_text << ":\n"
          << help.stdout_text;
    }
    // An option line is its spelling and value ("  --seed UINT=1"), then two spaces and its
    // description, or the description on the next line, indented.
    const auto described_on_the_line = [](const std::string& option_line) {
      const std::size_t gap = option_line.find("  ", 2);
      return gap != std::string::npos &&
             option_line.find_first_not_of(' ', gap) != std::string::npos;
    };
    std::istringstream lines(help.stdout_text.substr(help.stdout_text.find("Options:")));
    std::string line, previous;
    while (std::getline(lines, line)) {
      if (previous.rfind("  -", 0) == 0 && !described_on_the_line(previous)) {
        EXPECT_EQ(line.rfind("      ", 0), 0u) << command << ": no description for " << previous;
      }
      previous = line;
    }
    if (previous.rfind("  -", 0) == 0) {
      EXPECT_TRUE(described_on_the_line(previous)) << command << ": " << previous;
    }
  }
  // The hidden command is no suggestion to a user who mistyped one.
  EXPECT_EQ(run_rtiow("bogus").stderr_text.find("bench-point"), std::string::npos);
}

// Help fits a terminal (issue 60): every line within the width asked ($COLUMNS), descriptions
// wrapped beside their options, and render's options in named groups rather than one list.
TEST(Cli, HelpFitsTheTerminalAndGroupsRendersOptions) {
  for (const char* columns : {"80", "100"}) {
    ::setenv("COLUMNS", columns, 1);
    for (const char* command :
         {"", "render ", "scene ", "merge ", "bench ", "bench-point ", "accuracy ", "diff "}) {
      const CommandResult help = run_rtiow(std::string(command) + "--help");
      std::istringstream lines(help.stdout_text);
      for (std::string line; std::getline(lines, line);) {
        // A usage line lists every option, as CLI11 writes it; everything else fits.
        if (line.rfind("Usage:", 0) == 0) continue;
        EXPECT_LE(line.size(), std::stoul(columns)) << command << "--help: " << line;
      }
    }
  }
  ::unsetenv("COLUMNS");
  const std::string render = run_rtiow("render --help").stdout_text;
  for (const char* group : {"Scene:", "Output:", "Sampling:", "Camera (each replaces the scene's):",
                            "Long renders:", "Speed and distribution:"}) {
    EXPECT_NE(render.find(std::string("\n") + group + "\n"), std::string::npos) << group;
  }
  // Only help itself is left in the catch-all group.
  const std::size_t options = render.find("\nOptions:\n");
  ASSERT_NE(options, std::string::npos);
  std::istringstream block(render.substr(options + 10, render.find("\n\n", options + 1) - options));
  std::vector<std::string> listed;
  for (std::string line; std::getline(block, line);) {
    if (line.rfind("  -", 0) == 0) listed.push_back(line);
  }
  ASSERT_EQ(listed.size(), 1u) << render;
  EXPECT_NE(listed[0].find("--help"), std::string::npos);
}

// docs/usage.md shows `rtiow --help` and `rtiow render --help`: they must be what the binary
// prints, or the docs have gone stale.
// The subcommands `rtiow --help` lists, in its order.
std::vector<std::string> subcommands() {
  const std::string help = run_rtiow("--help").stdout_text;
  std::vector<std::string> names;
  std::istringstream lines(help.substr(help.find("Subcommands:")));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    if (line.rfind("  ", 0) != 0) break;
    if (line.rfind("   ", 0) == 0) continue;  // a description wrapped onto its next line
    std::istringstream words(line);
    std::string name;
    words >> name;
    names.push_back(name);
  }
  return names;
}

// docs/usage.md shows every command's help as the binary prints it. It is generated:
// RTIOW_UPDATE_DOCS=1 build/bin/cli_tests --gtest_filter='Cli.TheDocs*' rewrites the stale
// blocks and adds a missing command's at the end of "Every command's options".
TEST(Cli, TheDocsShowEveryCommandsHelpAsTheBinaryPrintsIt) {
  ::setenv("COLUMNS", "80", 1);  // the docs show help as an 80-column terminal gets it
  const fs::path path = fs::path(RTIOW_SOURCE_DIR) / "docs" / "usage.md";
  std::string docs = slurp(path);
  const bool update = std::getenv("RTIOW_UPDATE_DOCS") != nullptr;
  auto trimmed = [](std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  };
  std::vector<std::string> all_args = {"--help"};
  for (const std::string& name : subcommands()) all_args.push_back(name + " --help");
  ASSERT_GE(all_args.size(), 7u) << "rtiow --help lists fewer commands than it has";
  for (const std::string& args : all_args) {
    const std::string printed = trimmed(run_rtiow(args).stdout_text);
    const std::string prompt = "$ build/bin/rtiow " + args + "\n";
    std::size_t begin = docs.find(prompt);
    if (begin == std::string::npos && update) {
      docs = trimmed(docs) + "\n\n```text\n" + prompt + "\n```\n";
      begin = docs.find(prompt);
    }
    ASSERT_NE(begin, std::string::npos) << "docs/usage.md does not show " << args;
    const std::size_t from = begin + prompt.size();
    const std::size_t to = docs.find("\n```", from);
    const std::string shown = docs.substr(from, to - from);
    if (update) {
      docs.replace(from, to - from, printed);
    } else {
      EXPECT_EQ(trimmed(shown), printed)
          << "docs/usage.md shows stale help for `rtiow " << args
          << "` (RTIOW_UPDATE_DOCS=1 build/bin/cli_tests --gtest_filter='Cli.TheDocs*')";
    }
  }
  if (update) std::ofstream(path, std::ios::binary) << docs;
}

// A line of program output with what varies between runs taken out: every number becomes N
// and the path after "->" or "wrote ... to" becomes PATH (the docs show another machine's).
std::string output_form(const std::string& line) {
  static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e[+-]?[0-9]+)?)");
  static const std::regex path(R"((-> |to )\S+)");
  return std::regex_replace(std::regex_replace(line, path, "$1PATH"), number, "N");
}

// A line of program output with only what a run's timing changes taken out: seconds, the rate
// and the thread count (a render is a pure function of its settings: its sample counts, rays
// and errors are not).
std::string timing_form(const std::string& line) {
  static const std::regex seconds(R"([0-9]+\.[0-9]+ s,)"), rate(R"([0-9.]+ Mrays/s)"),
      threads(R"([0-9]+ threads?)");
  return std::regex_replace(
      std::regex_replace(std::regex_replace(line, seconds, "T s,"), rate, "R Mrays/s"), threads,
      "N threads");
}

// The render examples of a page (docs/usage.md, README.md) print what the program prints. An
// example of a small render (a --width of at most 400, no --time-limit) is run as written, into
// a scratch directory, and must print the lines the page shows but for its timing; the others
// (the full cover, a time limit) are run at 16 pixels wide and must print them in form (numbers
// and paths aside). An example whose output is an error line must be refused (exit 2).
// RTIOW_UPDATE_DOCS=1 rewrites the small examples' output from the program. Returns how many
// examples were checked, and of those exactly.
std::pair<int, int> check_render_examples(const fs::path& path) {
  const std::string docs = slurp(path);
  const bool update = std::getenv("RTIOW_UPDATE_DOCS") != nullptr;
  const fs::path dir = empty_output_dir(test_name() + "-" + path.stem().string() + "-dir");
  const std::string prompt = "$ build/bin/rtiow render ";
  std::vector<std::string> lines;
  {
    std::istringstream in(docs);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::string rewritten;
  int checked = 0, exact = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& command = lines[i];
    rewritten += command + "\n";
    // Examples of one run's moment (a signal and the resumes after it) and the listings are not
    // re-run.
    if (command.rfind(prompt, 0) != 0 || command.find('#') != std::string::npos ||
        command.find("--resume") != std::string::npos ||
        command.find("--help") != std::string::npos ||
        command.find("--list-scenes") != std::string::npos) {
      continue;
    }
    std::size_t end = i + 1;
    while (end < lines.size() && lines[end].rfind("$ ", 0) != 0 && lines[end].rfind("```", 0) != 0)
      ++end;
    std::vector<std::string> shown;
    for (std::size_t k = i + 1; k < end; ++k) {
      if (lines[k] != "..." && lines[k].rfind("progress:", 0) != 0) shown.push_back(lines[k]);
    }
    const bool refused = !shown.empty() && shown[0].rfind("rtiow: error:", 0) == 0;
    std::string args = command.substr(prompt.size());
    std::smatch width;
    const bool small =
        refused || (std::regex_search(args, width, std::regex(R"(--width (\d+))")) &&
                    std::stoi(width[1]) <= 400 && args.find("--time-limit") == std::string::npos);
    if (!small) args = "--width 16 " + std::regex_replace(args, std::regex(R"(--width \d+)"), "");
    const CommandResult r = run_rtiow("render " + args, "cd " + dir.string() + " && ");
    EXPECT_EQ(r.exit_code, refused ? 2 : 0) << command << "\n" << r.stderr_text;
    std::vector<std::string> printed, printed_lines;
    std::istringstream out(r.stdout_text + r.stderr_text);
    for (std::string line; std::getline(out, line);) {
      if (line.rfind("progress:", 0) == 0) continue;
      printed_lines.push_back(line);
      printed.push_back(small ? timing_form(line) : output_form(line));
    }
    std::vector<std::string> expected;
    for (const std::string& line : shown) {
      expected.push_back(small ? timing_form(line) : output_form(line));
    }
    if (update && small) {
      for (const std::string& line : printed_lines) rewritten += line + "\n";
      i = end - 1;
    }
    if (!update) {
      EXPECT_EQ(expected, printed)
          << path.filename().string() << ": `" << command
          << "` shows other lines than the program prints"
          << (small ? " (RTIOW_UPDATE_DOCS=1 build/bin/cli_tests --gtest_filter='Cli.TheDocs*')"
                    : "");
    }
    ++checked;
    exact += small;
  }
  if (update) std::ofstream(path, std::ios::binary) << rewritten;
  return {checked, exact};
}

TEST(Cli, TheDocsRenderExamplesShowWhatTheProgramPrints) {
  const auto [checked, exact] =
      check_render_examples(fs::path(RTIOW_SOURCE_DIR) / "docs" / "usage.md");
  EXPECT_GE(checked, 8) << "the render examples were not found in docs/usage.md";
  EXPECT_GE(exact, 5) << "fewer render examples than expected are checked exactly";
}

// The README's examples too, each exactly (issue 60: its first render's ray count had drifted).
TEST(Cli, TheDocsOfTheReadmeShowWhatTheProgramPrints) {
  const auto [checked, exact] = check_render_examples(fs::path(RTIOW_SOURCE_DIR) / "README.md");
  EXPECT_GE(checked, 2) << "the render examples were not found in README.md";
  EXPECT_EQ(exact, checked) << "a README example is checked only in form";
}

// docs/diff.md's example comparisons print what `rtiow diff` prints, in form: two seeds with
// variance channels and two without, small, compared in each mode the docs show.
TEST(Cli, TheDiffDocsShowWhatTheProgramPrints) {
  const std::string docs = slurp(fs::path(RTIOW_SOURCE_DIR) / "docs" / "diff.md");
  std::vector<std::string> shown;
  std::istringstream lines(docs);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("noise-aware, ", 0) == 0 || line.rfind("plain: ", 0) == 0)
      shown.push_back(output_form(line));
  }
  const auto image = [](int seed, bool stats) {
    const fs::path p = output_path("s" + std::to_string(seed) + ".exr");
    const CommandResult r =
        run_rtiow("render -q --scene cover --width 32 --height 18 --spp 8 --seed " +
                  std::to_string(seed) + (stats ? " --stats-channels" : "") + " -o " + p.string());
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return p.string();
  };
  const std::string s3 = image(3, true), s4 = image(4, true), t1 = image(11, false),
                    t2 = image(12, false);
  std::vector<std::string> printed;
  for (const std::string& args : {"diff " + s3 + " " + s4,
                                  "diff " + s3 + " " + s4 +
                                      " --mode plain --fail 0.1 --failpercent 5 --warn 0.1 "
                                      "--warnpercent 5",
                                  "diff " + s3 + " " + t1 + " " + t2}) {
    const CommandResult r = run_rtiow(args);
    const std::string first = r.stdout_text.substr(0, r.stdout_text.find('\n'));
    printed.push_back(output_form(first));
    EXPECT_NE(std::find(shown.begin(), shown.end(), printed.back()), shown.end())
        << "docs/diff.md shows no line of the form `rtiow " << args << "` prints:\n"
        << first;
  }
  for (const std::string& form : shown) {
    EXPECT_NE(std::find(printed.begin(), printed.end(), form), printed.end())
        << "docs/diff.md shows a line the program no longer prints: " << form;
  }
}

// One version string: the program says the library's, which CMake's project(VERSION) sets.
TEST(Cli, TheVersionIsTheProjects) {
  EXPECT_EQ(run_rtiow("--version").stdout_text,
            std::string("rtiow ") + RTIOW_PROJECT_VERSION + "\n");
  EXPECT_STREQ(rtiow::version(), RTIOW_PROJECT_VERSION);
}

// Debian's OpenImageIO takes some 0.3 s of symbol binding to load: only commands that read or
// write an image may load it. The dynamic loader's own log (LD_DEBUG=files) says what was.
TEST(Cli, OnlyCommandsThatTouchImagesLoadOpenImageIO) {
  const auto loads_oiio = [](const std::string& args) {
    const CommandResult r = run_rtiow(args, "LD_DEBUG=files ");
    return r.stderr_text.find("libOpenImageIO") != std::string::npos;
  };
  const fs::path scene = output_path("scene.json");
  EXPECT_FALSE(loads_oiio("--version"));
  EXPECT_FALSE(loads_oiio("render --help"));
  EXPECT_FALSE(loads_oiio("scene cover -o " + scene.string()));
  EXPECT_FALSE(loads_oiio("render --scene cover --width -3 -o " + output_path("x.png").string()));
  EXPECT_FALSE(
      loads_oiio("render " + scene.string() + ".missing -o " + output_path("y.png").string()));
  // A PNG render neither: rtiow encodes PNG itself (core/io/png_encoder.h).
  EXPECT_FALSE(loads_oiio("render -q --scene cover --width 8 --height 8 --spp 1 -o " +
                          output_path("z.png").string()));
  // ...and a render to another format does load it, so the checks above can see it.
  EXPECT_TRUE(loads_oiio("render -q --scene cover --width 8 --height 8 --spp 1 -o " +
                         output_path("z.jpg").string()));
}

// A program without its image backend says so before a render that needs it, and writes
// nothing; a PNG render, which rtiow encodes itself, does not need it.
TEST(Cli, AMissingImageBackendIsReportedBeforeTheRender) {
  const fs::path root = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + "-install");
  fs::remove_all(root);
  fs::create_directories(root / "bin");
  fs::copy_file(RTIOW_BINARY, root / "bin" / "rtiow");
  const auto render_to = [&](const fs::path& image) {
    const std::string command = (root / "bin" / "rtiow").string() +
                                " render -q --scene cover --width 8 --height 8 --spp 1 -o " +
                                image.string() + " 2> " + (root / "err").string();
    return WEXITSTATUS(std::system(command.c_str()));
  };
  const fs::path image = root / "x.jpg";
  EXPECT_NE(render_to(image), 0);
  EXPECT_FALSE(fs::exists(image));
  const std::string err = slurp(root / "err");
  EXPECT_NE(err.find("librtiow_image_io.so"), std::string::npos) << err;
  EXPECT_EQ(count_lines(err), 1) << err;

  EXPECT_EQ(render_to(root / "x.png"), 0) << slurp(root / "err");
  EXPECT_TRUE(fs::exists(root / "x.png"));
}

// rtiow diff's exit codes, idiff's: 0 for two seeds, 2 (FAILURE) for a turned camera; no
// verdict, and one line: 3 for images that cannot be compared, 4 for a file or option it
// cannot use, so `! rtiow diff ...` never passes on a typo.
TEST(Cli, DiffPassesOtherSeedsFailsAMutationAndRefusesMismatches) {
  const std::string render =
      "render -q --scene cover --width 64 --height 36 --spp 16 --stats-channels ";
  const fs::path a = output_path("a.exr"), b = output_path("b.exr"), turned = output_path("t.exr"),
                 small = output_path("s.exr");
  ASSERT_EQ(run_rtiow(render + "--seed 3 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 4 -o " + b.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 4 --lookat 0.236,0,0 -o " + turned.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 32 --height 18 --spp 4 -o " + small.string())
                .exit_code,
            0);
  const CommandResult same = run_rtiow("diff " + a.string() + " " + b.string());
  EXPECT_EQ(same.exit_code, 0) << same.stdout_text;
  EXPECT_NE(same.stdout_text.find("noise-aware"), std::string::npos);
  const CommandResult mutated = run_rtiow("diff " + a.string() + " " + turned.string());
  EXPECT_EQ(mutated.exit_code, 2) << mutated.stdout_text;
  const CommandResult refused = run_rtiow("diff " + a.string() + " " + small.string());
  EXPECT_EQ(refused.exit_code, 3);
  EXPECT_EQ(count_lines(refused.stderr_text), 1) << refused.stderr_text;
  EXPECT_NE(refused.stderr_text.find("differ in size"), std::string::npos);
  const CommandResult missing = run_rtiow("diff " + a.string() + " /nonexistent.exr");
  EXPECT_EQ(missing.exit_code, 4);
  EXPECT_EQ(count_lines(missing.stderr_text), 1) << missing.stderr_text;
  EXPECT_EQ(missing.stdout_text.find("FAILURE"), std::string::npos) << missing.stdout_text;
  EXPECT_EQ(run_rtiow("diff --mdoe plain " + a.string() + " " + b.string()).exit_code, 4);
  EXPECT_EQ(run_rtiow("diff " + a.string()).exit_code, 4) << "no test image";

  // Several renders: compared by their spread (Student's t); a mismatched one is named.
  const CommandResult seeds =
      run_rtiow("diff " + a.string() + " " + b.string() + " " + turned.string() + " " + a.string());
  EXPECT_NE(seeds.stdout_text.find("from 3 renders (t, 2 d.o.f.)"), std::string::npos)
      << seeds.stdout_text;
  const CommandResult mixed =
      run_rtiow("diff " + a.string() + " " + b.string() + " " + small.string());
  EXPECT_EQ(mixed.exit_code, 3);
  EXPECT_EQ(count_lines(mixed.stderr_text), 1) << mixed.stderr_text;
  EXPECT_NE(mixed.stderr_text.find("-s.exr' against the reference"), std::string::npos)
      << mixed.stderr_text;
  const CommandResult plain_of_several =
      run_rtiow("diff --mode plain " + a.string() + " " + b.string() + " " + b.string());
  EXPECT_EQ(plain_of_several.exit_code, 4);
  EXPECT_NE(plain_of_several.stderr_text.find("--mode seeds"), std::string::npos);
  EXPECT_EQ(run_rtiow("diff --mode seeds " + a.string() + " " + b.string()).exit_code, 4);
  // Thresholds and alpha are finite amounts: NaN would make every comparison false.
  for (const char* option : {"--alpha nan", "--fail nan", "--hardfail inf", "--warn -1"}) {
    const CommandResult r =
        run_rtiow(std::string("diff ") + option + " " + a.string() + " " + b.string());
    EXPECT_EQ(r.exit_code, 4) << option;
    EXPECT_EQ(count_lines(r.stderr_text), 1) << option << ": " << r.stderr_text;
  }
}

// Plain thresholds given for failure alone: the warning ones follow them (idiff's --warn
// defaults to 1e-6, which would make every image of two seeds WARN).
TEST(Cli, DiffWarningThresholdsFollowTheFailureOnesGiven) {
  const std::string render = "render -q --scene cover --width 48 --height 27 --spp 8 ";
  const fs::path a = output_path("warn-a.png"), b = output_path("warn-b.png");
  ASSERT_EQ(run_rtiow(render + "--seed 1 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 2 -o " + b.string()).exit_code, 0);
  const std::string both = " " + a.string() + " " + b.string();
  const CommandResult loose = run_rtiow("diff --mode plain --fail 1 --failpercent 100" + both);
  EXPECT_EQ(loose.exit_code, 0) << loose.stdout_text;
  EXPECT_NE(loose.stdout_text.find("PASS"), std::string::npos) << loose.stdout_text;
  // A warning threshold given still counts on its own.
  const CommandResult warned =
      run_rtiow("diff --mode plain --fail 1 --failpercent 100 --warn 0.001 --warnpercent 1" + both);
  EXPECT_EQ(warned.exit_code, 1) << warned.stdout_text;
  EXPECT_NE(warned.stdout_text.find("WARNING"), std::string::npos) << warned.stdout_text;
}

// A PNG whose header claims `side` x `side` pixels and holds none.
std::string png_claiming(std::uint32_t side) {
  const auto crc32 = [](const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const unsigned char b : bytes) {
      crc ^= b;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  const auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  const std::string header = be32(side) + be32(side) + std::string{8, 2, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) +
         chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + chunk("IEND", "");
}

// A header that lies about its size is refused before anything is allocated.
TEST(Cli, DiffRefusesAnImageWhoseHeaderClaimsTooManyPixels) {
  const fs::path huge = output_path("huge.png"), small = output_path("small.png");
  rtiow::test::write_file(huge, png_claiming(1000000));
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 8 --height 8 --spp 1 -o " + small.string())
                .exit_code,
            0);
  const CommandResult r = run_rtiow("diff " + huge.string() + " " + small.string());
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("pixels"), std::string::npos) << r.stderr_text;

  // A truncated PNG: libpng's own complaint stays off stderr, OpenImageIO's joins the line.
  const fs::path truncated = output_path("truncated.png");
  rtiow::test::write_file(truncated, png_claiming(8).substr(0, 40));
  const CommandResult cut = run_rtiow("diff " + small.string() + " " + truncated.string());
  EXPECT_EQ(cut.exit_code, 4);
  EXPECT_EQ(count_lines(cut.stderr_text), 1) << cut.stderr_text;
}

TEST(Cli, ListsTheBuiltinScenes) {
  const CommandResult r = run_rtiow("render --list-scenes");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* scene : {"materials", "wide-angle", "viewpoint", "defocus", "cover"}) {
    EXPECT_NE(r.stdout_text.find(scene), std::string::npos) << scene;
  }
}

TEST(Cli, RefusesBadCamerasAndSettingsWithOneLineAndExitTwo) {
  expect_refused("--scene materials --lookfrom 0,0,-1", "lookfrom equals lookat");
  expect_refused("--scene materials --vup 0,0,-1", "vup is parallel");
  expect_refused("--vfov 0", "vfov");
  expect_refused("--vfov 180", "vfov");
  expect_refused("--width 0", "width");
  expect_refused("--spp 0", "spp");
  expect_refused("--spp -4", "spp");
  expect_refused("--scene nowhere", "unknown scene 'nowhere'");
  expect_refused("--accel magic", "unknown accelerator");
  expect_refused("--width ten", "--width");
  expect_refused("--no-such-option", "no-such-option");
}

// A slip gets the nearest real name, a value of the wrong kind the kind expected, and the
// hint names the help of the command used (issue 43: the top-level help lists no render option).
TEST(Cli, OptionErrorsSuggestWhatWasMeant) {
  expect_refused("--widht 100", "unknown option '--widht' for rtiow render; did you mean --width?");
  expect_refused("--sed 3", "did you mean --seed?");
  expect_refused("--acel naive", "did you mean --accel?");
  expect_refused("--width=100x", "--width expects a whole number, not '100x'");
  expect_refused("--spp ten", "--spp expects a whole number, not 'ten' (see rtiow render --help)");
  // A whole number beyond the option's type: the range, not "expects a whole number".
  expect_refused("--spp 99999999999",
                 "--spp: '99999999999' is beyond the largest value it takes, 2147483647");
  expect_refused("--target-error often", "--target-error: must be a finite number");
  // Too few or too many values for a vector: how many, and how to write them.
  expect_refused("--lookfrom 1,2",
                 "--lookfrom takes 3 numbers, got 2 (as --lookfrom 1,2,3, with commas or spaces "
                 "between; see rtiow render --help)");
  expect_refused("--vup 0 1 0 0", "--vup takes 3 numbers, got 4");
  // A value outside an option's choices: the choices in words and the one meant.
  expect_refused("--sampler sobel",
                 "--sampler: 'sobel' is not one of independent, sobol, padded-sobol; did you mean "
                 "sobol? (see rtiow render --help)");
  expect_refused("--roulette of", "did you mean off?");
  expect_refused("--fresnel schlik", "did you mean schlick?");
  expect_refused("--accel embre", "unknown accelerator 'embre'; did you mean embree?");
  // Nothing near enough: no suggestion.
  const CommandResult far = run_rtiow("render --zzzzzz 1");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.stderr_text.find("did you mean"), std::string::npos) << far.stderr_text;
  // The other commands and rtiow itself.
  const CommandResult diff = run_rtiow("diff --alfa 0.1 a.png b.png");
  EXPECT_NE(diff.stderr_text.find("did you mean --alpha? (see rtiow diff --help)"),
            std::string::npos)
      << diff.stderr_text;
  const CommandResult mode = run_rtiow("diff --mode nois a.png b.png");
  EXPECT_EQ(mode.exit_code, 4) << "diff's 2 is a FAILURE verdict";
  EXPECT_NE(mode.stderr_text.find("did you mean noise? (see rtiow diff --help)"), std::string::npos)
      << mode.stderr_text;
  const CommandResult version = run_rtiow("--verison");
  EXPECT_EQ(version.exit_code, 2);
  EXPECT_NE(version.stderr_text.find("did you mean --version?"), std::string::npos)
      << version.stderr_text;
  const CommandResult command = run_rtiow("rendr --spp 4");
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_NE(command.stderr_text.find("unknown command 'rendr'; did you mean render?"),
            std::string::npos)
      << command.stderr_text;
}

// The natural slips between a scene's name and a scene file, and a scene written as an image.
TEST(Cli, SceneNamesAndFilesPointToEachOther) {
  expect_refused("cover",
                 "no scene file 'cover'; the built-in scene is rendered with --scene cover");
  expect_refused("--scene base.json", "a scene file is given by its path, without --scene");
  expect_refused("--scene covr", "unknown scene 'covr'; did you mean cover?");
  const fs::path png = output_path("scene.png");
  const CommandResult r = run_rtiow("scene cover -o " + png.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("a scene is JSON, not an image"), std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(png));
}

// A refine from 25% to 100% of its samples, at 30% after one second: 70% to go at 5% a second
// is 14 s (counting the checkpoint's 25% as this run's work said 2.3 s, issue 43).
TEST(Cli, TheTimeToGoCountsOnlyThisRunsWork) {
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(300, 250, 1000, 1.0), 14.0);
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(300, 0, 1000, 1.0), 7.0 / 3.0);  // a fresh render
  EXPECT_LT(rtiow::seconds_to_go(250, 250, 1000, 1.0), 0.0);             // no rate yet
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(1000, 250, 1000, 3.0), 0.0);
}

// Every mode shows how far it is toward its end (issue 60): the share of its samples, budget or
// time, the time to go where one is honest, and the error targets' figures.
TEST(Cli, EveryModeShowsHowFarItIsTowardItsEnd) {
  using rtiow::ProgressSnapshot;
  rtiow::RenderSettings s;
  s.width = 10, s.height = 10;
  ProgressSnapshot now;
  now.samples_done = 2500, now.elapsed = 1.0, now.loop_seconds = 0.9;
  s.samples = rtiow::FixedSamples{100};
  rtiow::ProgressStatus p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.25);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 3.0);
  // With a time limit, whichever end is nearer.
  s.time_limit_seconds = 10.0, now.loop_seconds = 8.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.8);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 2.0);
  // A time limit alone, resumed after 5 s: the limit counts those.
  s.samples = rtiow::UntilTimeLimit{}, now.loop_seconds = 2.5, now.seconds_before = 5.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.75);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 2.5);
  // --adaptive's budget: unknown until the first round is judged, then in rays.
  s.time_limit_seconds = 0.0, now.seconds_before = 0.0;
  s.samples = rtiow::AdaptiveBudget{100, 16};
  now.rays_traced = 200000, now.loop_seconds = 2.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_LT(p.fraction, 0.0);
  EXPECT_LT(p.seconds_to_go, 0.0);
  now.budget_rays = 1e6, now.spent_rays = 2e5, now.rays_at_judgement = 200000;
  now.rays_traced = 500000, now.loop_seconds = 5.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.5);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 5.0);
  // The error targets: the error reached against the one asked, and no time to go.
  s.samples = rtiow::ImageErrorTarget{0.02, 8192, 16};
  p = rtiow::progress_status(s, 100, now);
  EXPECT_EQ(p.detail, "error ? (asked 0.02)");
  now.image_error = 0.031;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_EQ(p.detail, "error 0.031 (asked 0.02)");
  EXPECT_LT(p.fraction, 0.0);
  EXPECT_LT(p.seconds_to_go, 0.0);
  s.samples = rtiow::PixelErrorTarget{0.05, 8192, 16}, now.pixels_above_target = 37;
  EXPECT_EQ(rtiow::progress_status(s, 100, now).detail, "37 of 100 pixels above error 0.05");
  s.time_limit_seconds = 10.0;  // and a time limit's share beside it
  EXPECT_DOUBLE_EQ(rtiow::progress_status(s, 100, now).fraction, 0.5);
}

// What a log shows of each mode: a share and an ETA, or the error against the one asked; and a
// zero error target, which no render reaches, is refused rather than taken as "off".
TEST(Cli, AdaptiveAndTimedRendersShowProgressInALog) {
  // Each long enough for a log's line (one a second at most).
  const std::string base = "render --scene cover --width 160 --height 90 --checkpoint 0 -o ";
  for (const char* mode : {" --time-limit 2.5", " --adaptive --spp 800"}) {
    const CommandResult r = run_rtiow(base + output_path("share.png").string() + mode);
    ASSERT_EQ(r.exit_code, 0) << mode << ": " << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("%  elapsed"), std::string::npos) << mode << ": " << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("ETA "), std::string::npos) << mode << ": " << r.stderr_text;
  }
  const CommandResult error =
      run_rtiow(base + output_path("error.png").string() + " --image-error 0.01");
  ASSERT_EQ(error.exit_code, 0) << error.stderr_text;
  EXPECT_NE(error.stderr_text.find("progress: "), std::string::npos) << error.stderr_text;
  EXPECT_NE(error.stderr_text.find("(asked 0.01)"), std::string::npos) << error.stderr_text;
  for (const char* option : {"--image-error 0", "--target-error 0"}) {
    const CommandResult zero = run_rtiow(base + output_path("zero.png").string() + " " + option);
    EXPECT_EQ(zero.exit_code, 2) << option;
    EXPECT_NE(zero.stderr_text.find("must be a finite number > 0"), std::string::npos)
        << zero.stderr_text;
  }
}

// --preview (issue 61): the output is replaced while the render runs, each preview a whole
// image whose metadata says how far the render is; the finished file is the one a render
// without --preview writes, byte for byte, and nothing else is left.
TEST(Cli, APreviewShowsTheRenderAsItGoesAndTheFinishedFileIsTheSame) {
  const fs::path dir = empty_output_dir(test_name() + "-dir");
  const fs::path watched = dir / "watched.exr";
  BackgroundRender r({"render", "-q", "--scene", "cover", "--width", "160", "--spp", "1000000",
                      "--checkpoint", "0", "--preview", "0.1", "--passes", "depth", "-o",
                      watched.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  std::string how_far;
  for (int i = 0; i < 1000 && how_far.empty(); ++i) {  // within 20 s
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::error_code none;
    if (!fs::exists(watched, none)) continue;
    auto in = OIIO::ImageInput::open(watched.string());
    ASSERT_TRUE(in) << "a preview is a whole image";
    how_far = in->spec().get_string_attribute("rtiow:preview");
    EXPECT_EQ(in->spec().width, 160);
    EXPECT_GE(in->spec().channelindex("Z"), 0) << "a preview holds the passes";
  }
  EXPECT_NE(how_far.find(" of 1000000 spp after "), std::string::npos) << how_far;
  r.signal(SIGTERM);
  EXPECT_EQ(r.wait(60.0), 128 + SIGTERM) << r.stderr_text();
  EXPECT_EQ(rtiow::test::names_in(dir), std::vector<std::string>{"watched.exr"});

  // A render of several passes, previewed at every pass, and the same render unwatched (with
  // the albedo, normal and depth passes, which the previews hold too).
  const std::string job =
      "render -q --scene cover --width 200 --spp 400 --reproducible --passes "
      "albedo,normal,depth -o ";
  const CommandResult w =
      run_rtiow(job + (dir / "w.exr").string() + " --preview 0.01 --checkpoint 0.01");
  ASSERT_EQ(w.exit_code, 0) << w.stderr_text;
  ASSERT_EQ(run_rtiow(job + (dir / "plain.exr").string()).exit_code, 0);
  EXPECT_TRUE(slurp(dir / "w.exr") == slurp(dir / "plain.exr")) << "the watched file differs";
  EXPECT_EQ(rtiow::test::names_in(dir),
            (std::vector<std::string>{"plain.exr", "w.exr", "watched.exr"}));
  // A share of a render is no image to watch.
  const CommandResult part = run_rtiow("render -q --width 16 --spp 4 --part 0/2 --preview 1 -o " +
                                       (dir / "p.exr").string());
  EXPECT_EQ(part.exit_code, 2);
  EXPECT_NE(part.stderr_text.find("--preview shows a whole render"), std::string::npos)
      << part.stderr_text;
}

TEST(Cli, RefusesUnwritableOutputsBeforeRendering) {
  const CommandResult bad_ext =
      run_rtiow("render -q --spp 1 --width 8 -o " + output_path("image.nosuchformat").string());
  EXPECT_EQ(bad_ext.exit_code, 2);
  EXPECT_NE(bad_ext.stderr_text.find("not an image format rtiow writes"), std::string::npos);
  const CommandResult bad_dir = run_rtiow("render -q --spp 1 --width 8 -o /nonexistent-dir/x.png");
  EXPECT_EQ(bad_dir.exit_code, 2);
  EXPECT_NE(bad_dir.stderr_text.find("does not exist"), std::string::npos);
}

// The pixels of an .exr the command line wrote.
std::vector<float> exr_pixels(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  width = in->spec().width, height = in->spec().height;
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data());
  return rgb;
}

// The region X0,Y0,X1,Y1 of an image of `width` floats a pixel (RGB).
std::vector<float> region_of(const std::vector<float>& rgb, int width, int x0, int y0, int x1,
                             int y1) {
  std::vector<float> region;
  for (int y = y0; y < y1; ++y) {
    const auto row = rgb.begin() + std::ptrdiff_t((std::size_t(y) * std::size_t(width)) * 3);
    region.insert(region.end(), row + x0 * 3, row + x1 * 3);
  }
  return region;
}

// --crop renders the whole image's pixels in its region, bit for bit: into EXR (which keeps
// the region's place in the frame) and PNG (the region alone), by parts merged, resumed from
// a kept checkpoint, and again with --like; a region outside the image and an adaptive crop
// are refused before any work.
TEST(Cli, ACropRendersTheWholeImagesPixelsInEveryWayARenderIsMade) {
  const fs::path dir = empty_output_dir("crop");
  const auto at = [&](const std::string& name) { return (dir / name).string(); };
  const std::string base = "render -q --scene cover --width 64 --spp 6 --reproducible ";
  const std::string crop = " --crop 10,5,40,27";
  ASSERT_EQ(run_rtiow(base + "-o " + at("full.exr")).exit_code, 0);
  ASSERT_EQ(run_rtiow(base + "-o " + at("full.png")).exit_code, 0);
  CommandResult r = run_rtiow(base + crop + " -o " + at("crop.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  int width = 0, height = 0, w = 0, h = 0;
  const std::vector<float> full = exr_pixels(at("full.exr"), width, height);
  const std::vector<float> expected = region_of(full, width, 10, 5, 40, 27);
  EXPECT_EQ(exr_pixels(at("crop.exr"), w, h), expected) << "the crop's pixels are not the image's";
  EXPECT_EQ(w, 30);
  EXPECT_EQ(h, 22);
  {
    auto in = OIIO::ImageInput::open(at("crop.exr"));
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.x, 10);
    EXPECT_EQ(spec.y, 5);
    EXPECT_EQ(spec.full_width, 64);
    EXPECT_EQ(spec.full_height, 43);
    EXPECT_EQ(spec.get_string_attribute("rtiow:crop"), "10,5,40,27");
    EXPECT_EQ(spec.get_string_attribute("rtiow:frame"), "64x43");
  }
  // PNG: the region alone, its bytes the whole PNG's there.
  ASSERT_EQ(run_rtiow(base + crop + " -o " + at("crop.png")).exit_code, 0);
  {
    OIIO::ImageBuf whole(at("full.png")), region(at("crop.png"));
    ASSERT_TRUE(whole.read() && region.read());
    EXPECT_EQ(region.spec().width, 30);
    EXPECT_EQ(region.spec().x, 0);
    std::vector<unsigned char> a(30 * 22 * 3), b(30 * 22 * 3);
    whole.get_pixels(OIIO::ROI(10, 40, 5, 27, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, a.data());
    region.get_pixels(OIIO::ROI(0, 30, 0, 22, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, b.data());
    EXPECT_EQ(a, b);
  }
  // Two parts of the crop, merged: the crop's file, byte for byte.
  for (const char* part : {"0/2", "1/2"}) {
    r = run_rtiow(base + crop + " --part " + part + " -o " +
                  at(std::string("part") + part[0] + ".exr"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  }
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("part1.exr") + " -o " + at("merged.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("merged.exr")), slurp(at("crop.exr"))) << "merged parts differ";
  // A part of another region does not merge with these.
  ASSERT_EQ(run_rtiow(base + " --crop 10,5,40,28 --part 1/2 -o " + at("other.exr")).exit_code, 0);
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("other.exr") + " -o " + at("no.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("no.exr")));
  // Refined from a kept checkpoint: 3 spp kept, resumed to 6.
  const std::string resumable = "render -q --scene cover --width 64 --reproducible" + crop;
  ASSERT_EQ(run_rtiow(resumable + " --spp 3 --keep-state -o " + at("resumed.exr")).exit_code, 0);
  r = run_rtiow(resumable + " --spp 6 --resume -o " + at("resumed.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("resumed.exr")), slurp(at("crop.exr"))) << "the resumed crop differs";
  // Again from the image's own record.
  r = run_rtiow("render -q --like " + at("crop.exr") + " -o " + at("like.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("like.exr")), slurp(at("crop.exr"))) << "--like lost the crop";

  r = run_rtiow(base + " --crop 10,5,70,27 -o " + at("outside.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("crop 10,5,70,27 is not a region of the 64x43 image"),
            std::string::npos)
      << r.stderr_text;
  r = run_rtiow("render -q --scene cover --width 64 --target-error 0.1 --crop 0,0,8,8 -o " +
                at("adaptive.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("uniform sampling only"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("outside.png")) || fs::exists(at("adaptive.png")));
}

// Channel `name` of an EXR, one float a pixel; empty when the file or the channel is missing.
std::vector<float> exr_channel(const fs::path& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const int c = in->spec().channelindex(name);
  if (c < 0) return {};
  std::vector<float> values(std::size_t(in->spec().width) * std::size_t(in->spec().height));
  in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, values.data());
  return values;
}

// --passes: the albedo, normal and depth channels beside an EXR's image, which they leave as it
// was; merged from parts, resumed from a checkpoint and repeated with --like to the same bytes
// as one render; refused where no channel fits, and a checkpoint without them is not resumed.
TEST(Cli, PassesAreWrittenBesideTheImageAndCombineLikeIt) {
  const fs::path dir = empty_output_dir("passes");
  const auto at = [&](const std::string& name) { return (dir / name).string(); };
  const std::string base = "render -q --scene cover --width 64 --reproducible ";
  const std::string passes = " --passes albedo,normal,depth";
  CommandResult r = run_rtiow(base + "--spp 6" + passes + " -o " + at("full.exr") +
                              " --summary-json " + at("summary.json"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  ASSERT_EQ(run_rtiow(base + "--spp 6 -o " + at("plain.exr")).exit_code, 0);
  int width = 0, height = 0, w = 0, h = 0;
  EXPECT_EQ(exr_pixels(at("full.exr"), width, height), exr_pixels(at("plain.exr"), w, h))
      << "the passes changed the image";
  {
    auto in = OIIO::ImageInput::open(at("full.exr"));
    ASSERT_TRUE(in);
    std::vector<std::string> names = in->spec().channelnames;
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B",
                                               "albedo.G", "albedo.R"}));
    EXPECT_EQ(in->spec().get_string_attribute("rtiow:passes"), "albedo,normal,depth");
  }
  // The cover's top-left pixel is sky: all 0; much of its bottom row sees only the ground: its
  // albedo of 0.5, the normal +y, and a distance.
  const std::vector<float> depth = exr_channel(at("full.exr"), "Z");
  const std::vector<float> ny = exr_channel(at("full.exr"), "N.Y");
  const std::vector<float> albedo = exr_channel(at("full.exr"), "albedo.G");
  ASSERT_EQ(depth.size(), std::size_t(width * height));
  EXPECT_EQ(depth[0], 0.0f);
  EXPECT_EQ(ny[0], 0.0f);
  EXPECT_EQ(albedo[0], 0.0f);
  int ground = 0;
  for (int x = 0; x < width; ++x) {
    const std::size_t p = std::size_t((height - 1) * width + x);
    if (albedo[p] == 0.5f && ny[p] > 0.9999f && depth[p] > 1.0f) ++ground;
  }
  EXPECT_GT(ground, width / 3);
  const auto summary = nlohmann::json::parse(slurp(at("summary.json")));
  EXPECT_EQ(summary["passes"], nlohmann::json({"albedo", "normal", "depth"}));

  // Two parts, merged: the one render's file, byte for byte.
  for (const char* part : {"0/2", "1/2"}) {
    r = run_rtiow(base + "--spp 6" + passes + " --part " + part + " -o " +
                  at(std::string("part") + part[0] + ".exr"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  }
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("part1.exr") + " -o " + at("merged.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("merged.exr")), slurp(at("full.exr"))) << "merged parts differ";
  // A part without the passes does not merge with one that has them.
  ASSERT_EQ(run_rtiow(base + "--spp 6 --part 1/2 -o " + at("bare.exr")).exit_code, 0);
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("bare.exr") + " -o " + at("no.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("with the same passes"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("no.exr")));

  // Resumed from a kept checkpoint: 3 spp kept, refined to 6.
  ASSERT_EQ(
      run_rtiow(base + "--spp 3 --keep-state" + passes + " -o " + at("resumed.exr")).exit_code, 0);
  r = run_rtiow(base + "--spp 6 --resume" + passes + " -o " + at("resumed.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("resumed.exr")), slurp(at("full.exr"))) << "the resumed passes differ";
  // A checkpoint kept without the passes has no sums for them: refused by name.
  ASSERT_EQ(run_rtiow(base + "--spp 3 --keep-state -o " + at("bare_state.exr")).exit_code, 0);
  r = run_rtiow(base + "--spp 6 --resume" + passes + " -o " + at("bare_state.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("passes (--passes): the checkpoint's 'none'"), std::string::npos)
      << r.stderr_text;

  // Again from the image's own record; into a PNG, which holds no passes, the image alone.
  r = run_rtiow("render -q --like " + at("full.exr") + " -o " + at("like.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("like.exr")), slurp(at("full.exr"))) << "--like lost the passes";
  r = run_rtiow("render -q --like " + at("full.exr") + " -o " + at("like.png"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;

  // Refused before any work: a format without channels, an unknown pass.
  r = run_rtiow(base + "--spp 1" + passes + " -o " + at("passes.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--passes: output"), std::string::npos) << r.stderr_text;
  r = run_rtiow(base + "--spp 1 --passes albedo,depht -o " + at("typo.exr"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("unknown pass 'depht'; did you mean depth?"), std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("passes.png")) || fs::exists(at("typo.exr")));
}

// The viewer's end of --display: a tev that accepts one connection on 127.0.0.1 and keeps
// every byte it is sent, until the sender closes (or a minute passes).
// A TCP socket bound to a free port of 127.0.0.1, listening when `listen` is asked; 0 for the
// port when that fails.
int bound_loopback_socket(bool listen, int& port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  const bool bound = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
                     (!listen || ::listen(fd, 1) == 0) &&
                     ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0;
  port = bound ? ntohs(address.sin_port) : 0;
  return fd;
}

class FakeTev {
 public:
  FakeTev() {
    listening_ = bound_loopback_socket(/*listen=*/true, port_);
    if (port_ == 0) return;
    reader_ = std::thread([this] {
      pollfd ready{listening_, POLLIN, 0};
      if (::poll(&ready, 1, 60000) <= 0) return;
      const int connection = ::accept(listening_, nullptr, nullptr);
      if (connection < 0) return;
      char buffer[1 << 16];
      for (ssize_t n; (n = ::recv(connection, buffer, sizeof buffer, 0)) > 0;) {
        bytes_.append(buffer, std::size_t(n));
      }
      ::close(connection);
    });
  }
  ~FakeTev() {
    if (reader_.joinable()) reader_.join();
    ::close(listening_);
  }
  int port() const { return port_; }
  // Everything received, once the sender has closed.
  const std::string& received() {
    if (reader_.joinable()) reader_.join();
    return bytes_;
  }

 private:
  int listening_ = -1;
  int port_ = 0;
  std::thread reader_;
  std::string bytes_;
};

// tev's packets, read as tev reads them: a 32-bit little-endian size (itself included), the
// type, the fields.
class TevReader {
 public:
  explicit TevReader(std::string_view bytes) : bytes_(bytes) {}
  bool next_packet() {
    at_ = end_;
    if (at_ + 5 > bytes_.size()) return false;
    end_ = at_ + std::size_t(integer<std::uint32_t>());
    if (end_ > bytes_.size() || end_ < at_ + 5) return false;
    type_ = bytes_[at_++];
    return true;
  }
  char type() const { return type_; }
  template <typename Int>
  Int integer() {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < sizeof(Int); ++i) {
      value |= std::uint64_t(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    }
    at_ += sizeof(Int);
    return static_cast<Int>(value);
  }
  float number() {
    const auto bits = integer<std::uint32_t>();
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  std::string text() {
    const std::size_t zero = bytes_.find('\0', at_);
    std::string value(bytes_.substr(at_, zero - at_));
    at_ = zero + 1;
    return value;
  }
  bool at_end() const { return at_ == end_; }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0, end_ = 0;
  char type_ = 0;
};

// What a viewer shows after every packet: the image tev made (CreateImage) with each update
// (UpdateImageV3, RGB interleaved) pasted in at its place.
struct ShownImage {
  std::string name;
  int width = 0, height = 0, updates = 0;
  std::vector<std::string> channels;
  std::vector<float> rgb;
  std::vector<std::vector<float>> extra;  // the channels after R, G, B, one float a pixel
  std::vector<std::pair<int, int>> update_places;
  std::string problem;  // "" when every packet was as tev expects
};

ShownImage replay_tev(const std::string& bytes) {
  ShownImage shown;
  TevReader in(bytes);
  while (in.next_packet()) {
    if (in.type() == 4) {  // CreateImage
      in.integer<std::uint8_t>();
      shown.name = in.text();
      shown.width = in.integer<std::int32_t>(), shown.height = in.integer<std::int32_t>();
      const int channels = in.integer<std::int32_t>();
      for (int c = 0; c < channels; ++c) shown.channels.push_back(in.text());
      if (channels < 3 || shown.channels[0] != "R" || shown.channels[1] != "G" ||
          shown.channels[2] != "B") {
        shown.problem = "an image whose first channels are not R, G, B";
        return shown;
      }
      const std::size_t pixels = std::size_t(shown.width) * std::size_t(shown.height);
      shown.rgb.assign(pixels * 3, -1.0f);
      shown.extra.assign(std::size_t(channels - 3), std::vector<float>(pixels, -1.0f));
    } else if (in.type() == 6) {  // UpdateImageV3
      in.integer<std::uint8_t>();
      if (in.text() != shown.name) shown.problem = "an update of another image";
      const int channels = in.integer<std::int32_t>();
      std::vector<std::string> names;
      for (int c = 0; c < channels; ++c) names.push_back(in.text());
      const int x = in.integer<std::int32_t>(), y = in.integer<std::int32_t>();
      const int w = in.integer<std::int32_t>(), h = in.integer<std::int32_t>();
      std::vector<std::int64_t> offsets(std::size_t(std::max(channels, 0)));
      std::vector<std::int64_t> strides(offsets.size());
      for (auto& o : offsets) o = in.integer<std::int64_t>();
      for (auto& s : strides) s = in.integer<std::int64_t>();
      bool interleaved = names == shown.channels;
      for (std::size_t c = 0; interleaved && c < offsets.size(); ++c) {
        interleaved = offsets[c] == std::int64_t(c) && strides[c] == channels;
      }
      if (!interleaved || x < 0 || y < 0 || x + w > shown.width || y + h > shown.height) {
        shown.problem = "an update outside the image, or not of its channels interleaved";
        return shown;
      }
      for (int row = 0; row < h; ++row) {
        for (int col = 0; col < w; ++col) {
          const std::size_t p =
              std::size_t(y + row) * std::size_t(shown.width) + std::size_t(x + col);
          for (int c = 0; c < channels; ++c) {
            const float v = in.number();
            if (c < 3) {
              shown.rgb[p * 3 + std::size_t(c)] = v;
            } else {
              shown.extra[std::size_t(c - 3)][p] = v;
            }
          }
        }
      }
      ++shown.updates;
      shown.update_places.emplace_back(x, y);
    } else {
      shown.problem = "a packet of type " + std::to_string(int(in.type()));
    }
    if (!in.at_end()) shown.problem = "a packet of another size than its fields";
  }
  return shown;
}

// --display: tev gets the image created at the frame's size, then its pixels as the render
// goes, the last of them the file's; a crop shows in its place; a viewer that is not there is
// a warning and the render is whole; a bad address is refused before any work.
TEST(Cli, DisplayShowsTheRenderInTevAsItGoes) {
  const fs::path out = output_path("displayed.exr");
  {
    FakeTev tev;
    ASSERT_GT(tev.port(), 0);
    const CommandResult r = run_rtiow(
        "render -q --scene cover --width 48 --spp 64 --reproducible --preview 0.001 "
        "--passes normal,depth --display 127.0.0.1:" +
        std::to_string(tev.port()) + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_EQ(r.stderr_text, "");
    const ShownImage shown = replay_tev(tev.received());
    EXPECT_EQ(shown.problem, "");
    EXPECT_EQ(shown.name, out.filename().string());
    EXPECT_EQ(shown.width, 48);
    EXPECT_EQ(shown.height, 32);
    EXPECT_GE(shown.updates, 1);
    int width = 0, height = 0;
    EXPECT_EQ(shown.rgb, exr_pixels(out, width, height)) << "tev shows other pixels than the file";
    // The passes as more channels, their values the file's.
    ASSERT_EQ(shown.channels, (std::vector<std::string>{"R", "G", "B", "N.X", "N.Y", "N.Z", "Z"}));
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(shown.extra[c], exr_channel(out, shown.channels[c + 3])) << shown.channels[c + 3];
    }
  }
  {
    FakeTev tev;
    const fs::path crop = output_path("displayed-crop.exr");
    const CommandResult r = run_rtiow(
        "render -q --scene cover --width 48 --spp 4 --crop 8,4,40,20 --display 127.0.0.1:" +
        std::to_string(tev.port()) + " -o " + crop.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const ShownImage shown = replay_tev(tev.received());
    EXPECT_EQ(shown.problem, "");
    EXPECT_EQ(shown.width, 48);
    ASSERT_FALSE(shown.update_places.empty());
    EXPECT_EQ(shown.update_places.back(), std::make_pair(8, 4));
  }
  // Nobody listening: the render is whole, with one warning.
  int port = 0;
  // A port that was free a moment ago, and is again once the probe closes.
  ::close(bound_loopback_socket(/*listen=*/false, port));
  ASSERT_GT(port, 0);
  const fs::path alone = output_path("displayed-alone.png");
  CommandResult r = run_rtiow("render -q --scene cover --width 16 --spp 2 --display 127.0.0.1:" +
                              std::to_string(port) + " -o " + alone.string());
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(fs::exists(alone));
  EXPECT_NE(r.stderr_text.find("warning: --display '127.0.0.1:" + std::to_string(port) +
                               "': cannot connect"),
            std::string::npos)
      << r.stderr_text;
  r = run_rtiow("render -q --width 16 --spp 2 --display localhost:99999 -o " +
                output_path("never.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--display 'localhost:99999': expected HOST:PORT"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(output_path("never.png")));
}

// One request, one image: the C++ API's resolve() and `rtiow render` give the same bits for
// the same request, defaults included (sampler, seed, the aspect rule, an error target's cap).
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
  EXPECT_EQ(j["schema"], 1);
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
  EXPECT_TRUE(j["error"].is_null());
  EXPECT_EQ(j["exit_code"], 0);
  EXPECT_GT(j["threads"].get<int>(), 0);
  EXPECT_GT(j["mrays_per_second"].get<double>(), 0.0);
  // An error target: the goal asked and the estimate reached, as the image records it.
  r = run_rtiow("render -q --width 48 --height 32 --image-error 0.05 -o " + out.string() +
                " --summary-json " + summary.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  j = nlohmann::json::parse(slurp(summary));
  in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(j["error"]["kind"], "image");
  EXPECT_EQ(j["error"]["asked"], 0.05);
  EXPECT_NEAR(j["error"]["estimated"].get<double>(),
              in->spec().get_float_attribute("rtiow:estimated_image_error"), 1e-6);
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
  EXPECT_EQ(j["schema"], 1);
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
      EXPECT_NE(spec.get_string_attribute("rtiow:camera").find("--vfov 60"), std::string::npos);
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
  EXPECT_NE(camera.find("--aperture 0 "), std::string::npos) << camera;
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
  ASSERT_EQ(run_rtiow("render -q edited.json --width 16 --spp 1 -o relative.png",
                      "cd " + elsewhere.string() + " && ")
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

namespace {

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
  EXPECT_NE(r.stdout_text.find("render / raw trace rate"), std::string::npos);
  EXPECT_NE(r.stdout_text.find("embree traversal alone"), std::string::npos);
  const std::string figures = slurp(json_path);
  for (const char* key : {"\"cover\"", "\"scaling\"", "\"trace\"", "\"traversal\"",
                          "\"embree_1_thread\"", "\"peak_rss_mb\"", "\"build_seconds\""}) {
    EXPECT_NE(figures.find(key), std::string::npos) << key;
  }
  EXPECT_TRUE(fs::exists(plot)) << r.stdout_text;

  // docs/performance.md shows a run of the program: each line this run prints has a line of
  // that form there (numbers, paths and alignment aside), and each line there but the ones of
  // a naive loop over its time budget is printed here.
  const auto form = [](const std::string& line) {
    return std::regex_replace(
        output_form(std::regex_replace(line, std::regex(R"(^(figures|plot): .*)"), "$1: PATH")),
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
  std::istringstream out(r.stdout_text);
  for (std::string line; std::getline(out, line);) {
    if (!line.empty()) printed.insert(form(line));
  }
  for (const std::string& line : printed) {
    EXPECT_TRUE(shown.count(line)) << "docs/performance.md has no line like: " << line;
  }
  for (const std::string& line : shown) {
    EXPECT_TRUE(printed.count(line)) << "rtiow bench prints no line like: " << line;
  }
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
  r = run_rtiow("accuracy -q --quick --width 48 --out " + (dir / "a").string() + " --cache-dir " +
                (dir / "cache").string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto accuracy = nlohmann::json::parse(slurp(dir / "a" / "accuracy.json"));
  EXPECT_EQ(accuracy["width"], 48);
  EXPECT_EQ(accuracy["max_spp"], 256);
  EXPECT_EQ(accuracy["reference_spp"], 1024);
  EXPECT_EQ(accuracy["repeat"], 1);
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
  EXPECT_EQ(bench["schema"], 1);
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
  EXPECT_EQ(accuracy["schema"], 1);
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
  for (const char* key : {"\"rmse_slope\"", "\"equal_time_factor\"", "\"budget_equal_time_factor\"",
                          "\"book_quality\"", "\"padded-sobol\"", "\"image_error\"",
                          "\"depth_sweep\"", "\"fresnel\"", "\"adaptive\"", "\"intersector\""}) {
    EXPECT_NE(figures.find(key), std::string::npos) << key;
  }
  const std::string csv = slurp(dir / "accuracy.csv");
  EXPECT_EQ(csv.rfind("group,choice,parameter", 0), 0u) << csv;
  // Header, 3 samplers x spp 1..64, 3 x budgets 32 and 64, the book's estimator at spp
  // 1..64, one image error, 3 depths, two intersectors, two Fresnel models, one target error.
  EXPECT_EQ(count_lines(csv), 1 + 3 * 7 + 3 * 2 + 7 + 1 + 3 + 2 + 2 + 1) << csv;
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

namespace {

std::vector<std::string> long_render(const fs::path& out) {
  // --restart: each case leaves its stopped render's checkpoint, which the next discards.
  return {"render", "--scene", "cover",     "--width", "160",
          "--spp",  "1000000", "--restart", "-o",      out.string()};
}

// Every signal that ends a process by default keeps the work: Ctrl-C, kill, a closed
// terminal or SSH session (HUP), SIGQUIT and a batch system's CPU-time limit (XCPU).
TEST(Cli, InterruptWritesTheSamplesCompleted) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU}) {
    SCOPED_TRACE(strsignal(sig));
    const fs::path out = output_path("interrupted.exr");
    // The signal must land in the sample loop: on a loaded machine the BVH's build may still
    // be under way after the first wait (a stop there writes nothing, rightly, and says so),
    // so the render is started again with a longer wait.
    std::optional<BackgroundRender> started;
    int code = 0;
    for (const int wait_ms : {500, 2000, 6000}) {
      started.emplace(long_render(out));
      ASSERT_TRUE(started->wait_until_rendering());
      std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
      started->signal(sig);
      code = started->wait(20.0);
      if (started->stderr_text().find("before the render began") == std::string::npos) break;
    }
    BackgroundRender& r = *started;
    EXPECT_EQ(code, 128 + sig) << r.stderr_text();
    EXPECT_NE(r.stderr_text().find("interrupted: wrote"), std::string::npos) << r.stderr_text();
    // stderr is no terminal here: no empty line, and no progress line after "stopping".
    const std::string text = r.stderr_text();
    EXPECT_EQ(text.find("\n\n"), std::string::npos) << text;
    EXPECT_NE(text.rfind("rtiow: stopping", 0) == 0 ? 0 : text.find("\nrtiow: stopping"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("progress:", text.find("rtiow: stopping")), std::string::npos) << text;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in) << "no partial image written";
    const OIIO::ImageSpec& spec = in->spec();
    const int spp = spec.get_int_attribute("rtiow:spp");
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 1000000);
    EXPECT_EQ(spec.get_int_attribute("rtiow:spp_requested"), 1000000);
    EXPECT_FALSE(spec.get_string_attribute("rtiow:stopped").empty());
    std::vector<float> pixels(std::size_t(spec.width * spec.height * 3));
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
    double sum = 0;
    for (float v : pixels) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    EXPECT_GT(sum / double(pixels.size()), 0.1) << "the partial image is not black";
  }
}

// A signal ignored when rtiow starts (nohup, a script's background job) stays ignored.
TEST(Cli, InheritedIgnoredSignalStaysIgnored) {
  const fs::path out = output_path("nohup.exr");
  BackgroundRender r(long_render(out), {SIGHUP});
  ASSERT_TRUE(r.wait_until_rendering());
  r.signal(SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  int status = 0;
  EXPECT_EQ(waitpid(r.pid(), &status, WNOHANG), 0) << "SIGHUP ended a render that ignores it";
  EXPECT_EQ(r.stderr_text().find("stopping"), std::string::npos) << r.stderr_text();
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(20.0), 128 + SIGINT) << r.stderr_text();
}

// A count that means days of work is accepted, but not silently: a note says how long and how
// to bound it; a render of ordinary length says nothing.
TEST(Cli, ARequestOfDaysSaysSoBeforeItStarts) {
  const fs::path out = output_path("days.png");
  BackgroundRender r({"render", "--scene", "cover", "--width", "160", "--spp", "2000000000", "-q",
                      "--checkpoint", "0", "-o", out.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(20.0), 128 + SIGINT) << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("rtiow: note: 2000000000 spp at 160x107"), std::string::npos)
      << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("days on a 2-core machine"), std::string::npos);
  const CommandResult ordinary = run_rtiow("render -q --scene cover --width 32 --spp 2 -o " +
                                           output_path("ordinary.png").string());
  EXPECT_EQ(ordinary.stderr_text, "");
}

// `rtiow scene cover | rtiow render -`: a scene on standard input renders as its file does, and
// a bad one is refused naming standard input.
// Two renders' files are the same image with the same provenance, but for the scene file one
// was read from (rtiow:scene_file), which `with_file` names.
void expect_same_but_scene_file(const fs::path& with_file, const fs::path& without,
                                const std::string& scene_file) {
  auto a = OIIO::ImageInput::open(with_file.string()), b = OIIO::ImageInput::open(without.string());
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->spec().get_string_attribute("rtiow:scene_file"), scene_file);
  EXPECT_EQ(b->spec().find_attribute("rtiow:scene_file"), nullptr);
  const auto attributes = [](const OIIO::ImageSpec& spec) {
    std::vector<std::string> all;
    for (const auto& attribute : spec.extra_attribs) {
      if (attribute.name() != "rtiow:scene_file")
        all.push_back(attribute.name().string() + "=" + attribute.get_string());
    }
    return all;
  };
  EXPECT_EQ(attributes(a->spec()), attributes(b->spec()));
  std::vector<float> pa(std::size_t(a->spec().image_pixels() * a->spec().nchannels)), pb(pa.size());
  ASSERT_TRUE(a->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pa.data()));
  ASSERT_TRUE(b->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pb.data()));
  EXPECT_EQ(pa, pb);
}

TEST(Cli, SceneFromStandardInputRendersAsItsFile) {
  const fs::path scene = output_path("scene.json"), piped = output_path("piped.png"),
                 direct = output_path("direct.png"), bad = output_path("bad.json");
  ASSERT_EQ(run_rtiow("scene cover --scene-seed 3 -o " + scene.string()).exit_code, 0);
  const std::string common = " --width 48 --spp 2 --reproducible -q ";
  const CommandResult p =
      run_rtiow("render -" + common + "-o " + piped.string() + " < " + scene.string());
  ASSERT_EQ(p.exit_code, 0) << p.stderr_text;
  ASSERT_EQ(
      run_rtiow("render --scene cover --scene-seed 3" + common + "-o " + direct.string()).exit_code,
      0);
  expect_same_but_scene_file(piped, direct, "-");
  {
    std::ofstream broken(bad);
    broken << "{\"version\": 1,";
  }
  const CommandResult b = run_rtiow("render -" + common + "-o " + output_path("bad.png").string() +
                                    " < " + bad.string());
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_EQ(b.stderr_text.rfind("rtiow: error: standard input: ", 0), 0u) << b.stderr_text;
}

// A plain diff of two seeds fails on their noise; it says which comparison tells noise from a
// change. A small local change says nothing of the kind.
TEST(Cli, PlainDiffOfTwoSeedsPointsToTheNoiseAwareModes) {
  const fs::path a = output_path("s3.png"), b = output_path("s4.png");
  const std::string common = "render -q --scene cover --width 48 --spp 4 ";
  ASSERT_EQ(run_rtiow(common + "--seed 3 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(common + "--seed 4 -o " + b.string()).exit_code, 0);
  const CommandResult d = run_rtiow("diff " + a.string() + " " + b.string());
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.stdout_text.find("--stats-channels"), std::string::npos) << d.stdout_text;
  EXPECT_NE(d.stdout_text.find("several renders"), std::string::npos) << d.stdout_text;
  const CommandResult explicit_plain =
      run_rtiow("diff --mode plain " + a.string() + " " + b.string());
  EXPECT_EQ(explicit_plain.stdout_text.find("note:"), std::string::npos)
      << "asked for plain: no advice";
}

TEST(Cli, SecondInterruptAbortsAndLeavesTheOldFileAlone) {
  const fs::path out = output_path("kept.png");
  {
    std::ofstream old(out, std::ios::binary);
    old << "the good image from before";
  }
  // Wide enough that the first pass (1 spp) outlasts both signals: the first must not get
  // to write before the second arrives.
  BackgroundRender r(
      {"render", "--scene", "cover", "--width", "3000", "--spp", "1000", "-o", out.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  // Past the scene's set-up (the lock is taken before it ends): a first signal there stops
  // the command before the render, with nothing for the second to cut short.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  r.signal(SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(5.0), 128 + SIGINT) << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("ended by signal 2"), std::string::npos) << r.stderr_text();
  EXPECT_EQ(slurp(out), "the good image from before");
}

}  // namespace

namespace {

TEST(Cli, RendersSceneFilesWithOverridesAndRefusesBadOnes) {
  const fs::path scene = output_path("scene.json");
  {
    std::ofstream out(scene);
    out << R"({"version": 1, "name": "file scene",
      "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
      "image": {"width": 20, "height": 10, "spp": 2, "depth": 4},
      "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]}},
      "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "red"}]})";
  }
  const fs::path out = output_path("from_file.exr");
  const CommandResult r = run_rtiow("render " + scene.string() + " --spp 3 -q -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 20) << "the file's width";
  EXPECT_EQ(in->spec().get_int_attribute("rtiow:spp"), 3) << "--spp overrides the file";
  EXPECT_EQ(in->spec().get_string_attribute("rtiow:scene"), "file scene");

  expect_refused(scene.string() + " --scene cover", "give a scene file or --scene, not both");
  {
    std::ofstream bad(scene);
    bad << R"({"version": 1, "spheres": []})";
  }
  expect_refused(scene.string(), scene.string() + ": /: missing field \"camera\"");
}

TEST(Cli, WrittenSceneFileRendersTheIdenticalFile) {
  const fs::path scene = output_path("cover7.json");
  ASSERT_EQ(run_rtiow("scene cover --scene-seed 7 -o " + scene.string()).exit_code, 0);
  const fs::path a = output_path("a.png"), b = output_path("b.png");
  const std::string common = " --width 48 --spp 2 --reproducible -q -o ";
  ASSERT_EQ(run_rtiow("render " + scene.string() + common + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render --scene cover --scene-seed 7" + common + b.string()).exit_code, 0);
  expect_same_but_scene_file(a, b, scene.string());
}

TEST(Cli, RefusesImagesTooLargeForMemoryBeforeAllocating) {
  expect_refused("--width 40000 --height 40000", "more than half of this machine's");
  expect_refused("--width 100000 --height 100000", "more than 2^31 pixels");
}

}  // namespace

namespace {

TEST(Cli, PartsMergeIntoTheIdenticalFileAndBadSetsAreRefused) {
  const std::string common = " --scene cover --width 64 --spp 12 --reproducible -q ";
  const fs::path whole = output_path("whole.png");
  ASSERT_EQ(run_rtiow("render" + common + "-o " + whole.string()).exit_code, 0);
  std::vector<fs::path> parts;
  for (int i = 0; i < 3; ++i) {
    parts.push_back(output_path("part" + std::to_string(i) + ".exr"));
    ASSERT_EQ(run_rtiow("render" + common + "--part " + std::to_string(i) + "/3 -o " +
                        parts.back().string())
                  .exit_code,
              0);
  }
  const fs::path merged = output_path("merged.png");
  // Given in any order.
  const CommandResult m = run_rtiow("merge " + parts[2].string() + " " + parts[0].string() + " " +
                                    parts[1].string() + " -o " + merged.string());
  ASSERT_EQ(m.exit_code, 0) << m.stderr_text;
  EXPECT_EQ(slurp(merged), slurp(whole)) << "merged parts differ from the single render";

  // The variances too: parts rendered with --stats-channels keep two replicates and their
  // exact spreads, so the merge writes the channels one render writes, bit for bit.
  const fs::path whole_stats = output_path("whole-stats.exr"),
                 merged_stats = output_path("merged-stats.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--stats-channels -o " + whole_stats.string()).exit_code,
            0);
  std::vector<fs::path> stats_parts;
  for (int i = 0; i < 3; ++i) {
    stats_parts.push_back(output_path("stats-part" + std::to_string(i) + ".exr"));
    ASSERT_EQ(run_rtiow("render" + common + "--stats-channels --part " + std::to_string(i) +
                        "/3 -o " + stats_parts.back().string())
                  .exit_code,
              0);
  }
  const CommandResult ms = run_rtiow("merge --stats-channels " + stats_parts[1].string() + " " +
                                     stats_parts[2].string() + " " + stats_parts[0].string() +
                                     " -o " + merged_stats.string());
  ASSERT_EQ(ms.exit_code, 0) << ms.stderr_text;
  EXPECT_EQ(slurp(merged_stats), slurp(whole_stats)) << "the merged variances differ";
  const CommandResult png_stats = run_rtiow(
      "merge --stats-channels " + stats_parts[0].string() + " " + stats_parts[1].string() + " " +
      stats_parts[2].string() + " -o " + output_path("stats.png").string());
  EXPECT_EQ(png_stats.exit_code, 2);
  EXPECT_NE(png_stats.stderr_text.find("must be .exr"), std::string::npos) << png_stats.stderr_text;
  // Parts drawn from one sequence (no --stats-channels) keep no estimate: refused by name.
  const CommandResult plain_stats =
      run_rtiow("merge --stats-channels " + parts[0].string() + " " + parts[1].string() + " " +
                parts[2].string() + " -o " + output_path("plain-stats.exr").string());
  EXPECT_EQ(plain_stats.exit_code, 2);
  EXPECT_NE(plain_stats.stderr_text.find("render them with --stats-channels"), std::string::npos)
      << plain_stats.stderr_text;
  // One sequence and two replicates are other samples: their parts do not merge.
  const CommandResult mixed =
      run_rtiow("merge " + parts[0].string() + " " + stats_parts[1].string() + " " +
                stats_parts[2].string() + " -o " + output_path("mixed.exr").string());
  EXPECT_EQ(mixed.exit_code, 2) << mixed.stderr_text;

  const fs::path early = output_path("early.exr"), late = output_path("late.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--sample-range 0:5 -o " + early.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render" + common + "--sample-range 3:12 -o " + late.string()).exit_code, 0);
  const fs::path out = output_path("refused.png");
  auto refused = [&](const std::string& files, const std::string& needle) {
    const CommandResult r = run_rtiow("merge " + files + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << files;
    EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
    EXPECT_FALSE(fs::exists(out));
  };
  refused(early.string() + " " + late.string(), "overlap: both hold samples [3, 5)");
  refused(parts[0].string() + " " + parts[2].string(), "samples [4, 8) are missing");
  refused(parts[1].string() + " " + parts[2].string(), "samples [0, 4) are missing");
  refused(whole.string(), "not a part file");
  const fs::path other = output_path("other.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--seed 2 --part 0/3 -o " + other.string()).exit_code, 0);
  refused(other.string() + " " + parts[1].string() + " " + parts[2].string(),
          "share of a different render");
  // Without the roulette other paths end: the book's estimator's part is another render's.
  const fs::path book = output_path("book-part.exr");
  ASSERT_EQ(
      run_rtiow("render" + common + "--roulette off --part 0/3 -o " + book.string()).exit_code, 0);
  refused(book.string() + " " + parts[1].string() + " " + parts[2].string(),
          "share of a different render");
  expect_refused("--part 0/3", "must be .exr");  // expect_refused writes a .png
  const fs::path part_out = output_path("refused.exr");
  for (const auto& [args, needle] :
       {std::pair<std::string, std::string>{"--part 3/3", "need 0 <= i < n"},
        {"--sample-range 5:5", "need A < B"},
        {"--sample-range 1-5", "expected A:B"},
        {"--part 0/3 --sample-range 0:4", "not both"}}) {
    const CommandResult r = run_rtiow("render -q -o " + part_out.string() + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
    EXPECT_FALSE(fs::exists(part_out));
  }
}

}  // namespace

namespace {

// A time-limited render's file says how many samples it holds, and it does hold them: the
// same render with exactly that --spp and no limit gives the same file.
TEST(Cli, TimeLimitedRenderHoldsTheSamplesItsMetadataSays) {
  const fs::path limited = output_path("limited.exr"), exact = output_path("exact.exr");
  const std::string common = "render -q --scene materials --width 64 --reproducible ";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(run_rtiow(common + "--time-limit 1 -o " + limited.string()).exit_code, 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 10.0) << "the limit was not honoured";
  auto in = OIIO::ImageInput::open(limited.string());
  ASSERT_TRUE(in);
  const int spp = in->spec().get_int_attribute("rtiow:spp");
  EXPECT_GT(spp, 1);
  EXPECT_NE(in->spec().get_string_attribute("rtiow:stopped").find("time limit"), std::string::npos);
  ASSERT_EQ(run_rtiow(common + "--spp " + std::to_string(spp) + " -o " + exact.string()).exit_code,
            0);
  std::vector<float> a(64 * 36 * 3), b(64 * 36 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, a.data()));
  auto other = OIIO::ImageInput::open(exact.string());
  ASSERT_TRUE(other && other->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, b.data()));
  EXPECT_EQ(a, b);
}

TEST(Cli, FresnelChoiceChangesGlassOnly) {
  const fs::path schlick = output_path("schlick.exr"), exact = output_path("exact.exr");
  const std::string common = "render -q --scene materials --width 48 --spp 16 --reproducible ";
  ASSERT_EQ(run_rtiow(common + "--fresnel schlick -o " + schlick.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(common + "--fresnel exact -o " + exact.string()).exit_code, 0);
  EXPECT_NE(slurp(schlick), slurp(exact));
  expect_refused("--fresnel fancy", "fresnel");
  const fs::path wide = output_path("wide.png"), wide_exact = output_path("wide_exact.png");
  const std::string no_glass = "render -q --scene wide-angle --width 32 --spp 4 --reproducible ";
  ASSERT_EQ(run_rtiow(no_glass + "-o " + wide.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(no_glass + "--fresnel exact -o " + wide_exact.string()).exit_code, 0);
  EXPECT_EQ(slurp(wide), slurp(wide_exact)) << "a scene without glass does not change";
}

}  // namespace

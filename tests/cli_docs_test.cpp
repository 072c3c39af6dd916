// Help and documentation as a user meets them: every command's --help true and readable,
// the docs' examples printing what the program prints, the version, and the image library
// loaded only where an image is touched.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <arpa/inet.h>
#include <embree3/rtcore_config.h>
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
#include "tests/cli_helpers.h"

namespace {

using namespace rtiow::test::cli;

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
         {"", "render ", "scene ", "merge ", "denoise ", "bench ", "bench-point ", "accuracy ",
          "diff "}) {
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
    const CommandResult r = run_rtiow("render " + args, dir.string());
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
    const fs::path p = output_path(std::string("s").append(std::to_string(seed)).append(".exr"));
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

// One version string: the program says the library's, which CMake's project(VERSION) sets,
// and then what was built in (issue 70): every fact the library gives, and MPI's.
TEST(Cli, TheVersionIsTheProjectsAndSaysWhatWasBuiltIn) {
  const std::string out = run_rtiow("--version").stdout_text;
  EXPECT_EQ(out.substr(0, out.find('\n')), std::string("rtiow ") + RTIOW_PROJECT_VERSION);
  EXPECT_STREQ(rtiow::version(), RTIOW_PROJECT_VERSION);
  const std::vector<std::string> facts = rtiow::build_facts();
  EXPECT_EQ(facts.size(), 4u);
  for (const std::string& fact : facts) {
    EXPECT_NE(out.find("\n" + fact + "\n"), std::string::npos) << fact << " not in\n" << out;
  }
  for (const std::string& said :
       {std::string("\ncompiler: GCC ") + __VERSION__, std::string("\noptimisation: "),
        std::string("\ninstruction sets: "), std::string("Embree ") + RTC_VERSION_STRING,
        std::string("oneTBB "), std::string("OpenImageIO "), std::string("\nMPI: ")}) {
    EXPECT_NE(out.find(said), std::string::npos) << said << " not in\n" << out;
  }
  // The commit the sources are at, looked up at every build (not at configure time, which
  // goes stale at the next commit).
  const std::size_t at = out.find("\ncommit: ");
  ASSERT_NE(at, std::string::npos) << out;
  const std::string commit = out.substr(at + 9, out.find('\n', at + 1) - at - 9);
  EXPECT_TRUE(std::regex_match(commit, std::regex("unknown|[0-9a-f]{12}(\\+changes)?"))) << commit;
  // git's own answer where the sources are a checkout: the commit is HEAD or one before it (a
  // build at one commit tested after the next is committed).
  rtiow::test::Launch git;
  git.argv = {"git", "-C", RTIOW_SOURCE_DIR, "rev-parse", "--git-dir"};
  if (commit != "unknown" && rtiow::test::launch(git) == 0) {
    git.argv = {"git", "-C", RTIOW_SOURCE_DIR, "merge-base", "--is-ancestor", commit.substr(0, 12),
                "HEAD"};
    EXPECT_EQ(rtiow::test::launch(git), 0) << commit << " is not HEAD or before it";
  }
}

// Debian's OpenImageIO takes some 0.3 s of symbol binding to load: only commands that read or
// write an image may load it. The dynamic loader's own log (LD_DEBUG=files) says what was.
TEST(Cli, OnlyCommandsThatTouchImagesLoadOpenImageIO) {
  const auto loads_oiio = [](const std::string& args) {
    const CommandResult r = run_rtiow(args, "", {"LD_DEBUG=files"});
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
    rtiow::test::Launch command;
    command.argv = rtiow::test::words((root / "bin" / "rtiow").string() +
                                      " render -q --scene cover --width 8 --height 8 --spp 1 -o " +
                                      image.string());
    command.stderr_path = (root / "err").string();
    return rtiow::test::launch(command);
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

}  // namespace

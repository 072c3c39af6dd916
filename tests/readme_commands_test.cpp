// The README's first two commands are the promises a newcomer meets first: the first builds
// the program alone and renders the cover (no test suite in the way of the first image), the
// second builds and runs everything, and CI (.ci/run) runs exactly the second.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The one-line commands of the README's first `sh` blocks, in order.
std::vector<std::string> readme_commands() {
  std::istringstream lines(slurp(fs::path(RTIOW_SOURCE_DIR) / "README.md"));
  std::vector<std::string> commands;
  bool in_block = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == "```sh") {
      in_block = true;
    } else if (line.rfind("```", 0) == 0) {
      in_block = false;
    } else if (in_block) {
      commands.push_back(line);
    }
  }
  return commands;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Readme, TheFirstCommandBuildsTheProgramAloneAndTheSecondEverything) {
  const std::vector<std::string> commands = readme_commands();
  ASSERT_GE(commands.size(), 2u);
  const std::string& first = commands[0];
  const std::string& second = commands[1];
  EXPECT_TRUE(has(first, "install-deps.sh --program")) << first;
  EXPECT_TRUE(has(first, "-DRTIOW_BUILD_TESTS=OFF")) << first;
  EXPECT_TRUE(has(first, "build/bin/rtiow render")) << first;
  EXPECT_FALSE(has(first, "ctest")) << first;
  // ON said outright: the build folder may hold the first command's OFF.
  EXPECT_TRUE(has(second, "-DRTIOW_BUILD_TESTS=ON")) << second;
  EXPECT_TRUE(has(second, "ctest --test-dir build")) << second;
  const std::string ci = slurp(fs::path(RTIOW_SOURCE_DIR) / ".ci" / "run");
  EXPECT_TRUE(has(ci, "\n" + second + "\n")) << ".ci/run does not run the README's second command";
}

// A manual apart from the notebook (issue 60): at most 10 KB, and no dated measurement log
// (those live in docs/performance.md and docs/accuracy.md).
TEST(Readme, IsAManualApartFromTheNotebook) {
  const std::string readme = slurp(fs::path(RTIOW_SOURCE_DIR) / "README.md");
  EXPECT_LE(readme.size(), 10u * 1024u);
  EXPECT_FALSE(has(readme, "2026-")) << "the README cites a dated measurement";
}

// The user's pages say how; the dated log is the measurement pages' own, after their figures.
TEST(Readme, TheUsersPagesCarryNoMeasurementLog) {
  const fs::path docs = fs::path(RTIOW_SOURCE_DIR) / "docs";
  for (const char* page : {"usage.md", "scene-format.md", "diff.md", "distributed.md", "library.md",
                           "robustness.md"}) {
    std::istringstream lines(slurp(docs / page));
    for (std::string line; std::getline(lines, line);) {
      const bool link = line.find("](") != std::string::npos;  // may cite a log's anchor
      EXPECT_FALSE(has(line, "2026-") && !link) << page << ": a dated line: " << line;
    }
  }
  for (const char* page : {"performance.md", "accuracy.md"}) {
    const std::string text = slurp(docs / page);
    const std::size_t log = text.find("\n## Measurement log\n");
    ASSERT_NE(log, std::string::npos) << page << " has no measurement log";
    std::istringstream lines(text.substr(0, log));
    for (std::string line; std::getline(lines, line);) {
      EXPECT_FALSE(line.rfind("## ", 0) == 0 && has(line, "(2026-"))
          << page << ": a dated section before the log: " << line;
    }
  }
}

}  // namespace

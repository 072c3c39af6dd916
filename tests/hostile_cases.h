#pragma once
// The hostile-input battery's cases (tests/hostile_input_test.cpp runs them): each a command
// a hostile user would type, the exit code of its class and a piece of the one line it must
// print, with the files and limits it runs among.

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace rtiow::test::hostile {

// The user's scene, which the cases render and the fixtures' part files are made from.
extern const char* const kScene;

// kScene with `from` replaced by `to` (a test fails if `from` is not in it).
std::string scene_with(const std::string& from, const std::string& to);

struct Case {
  std::string name;
  int exit_code;                               // 2: wrong input; 1: the machine failed
  std::string needle;                          // the error line must hold this
  std::vector<std::string> args;               // to rtiow, in the case's directory
  std::map<std::string, std::string> files{};  // more files of the user's
  std::vector<std::string> limits{};           // more prlimit options
  std::string stdout_path{};                   // default: a file outside the directory
};

// CTest lists each case by its name, not by the bytes of the struct.
inline void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

// Every case, class by class.
std::vector<Case> all_cases();

}  // namespace rtiow::test::hostile

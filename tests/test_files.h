#pragma once
// Whole files as strings, for the tests that run the executable and look at what it wrote.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rtiow::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

}  // namespace rtiow::test

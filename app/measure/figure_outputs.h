#pragma once
// The files a measurement command (bench, accuracy) writes into its --out directory, claimed
// before its minutes of work (core/io/output_claim.h): a second command aimed at the same
// files is refused at once rather than after its work, and every file is written through the
// claim's held directory. A directory the command made for them and left empty (it failed)
// is removed again: nothing is left that the user did not get.

#include <memory>
#include <string>
#include <vector>

namespace rtiow {

class OutputClaim;

class FigureOutputs {
 public:
  // Makes `directory` if it is missing and claims each of `names` in it. `option` names the
  // directory in errors ("--out").
  FigureOutputs(const std::string& directory, const std::vector<std::string>& names,
                const std::string& option);
  ~FigureOutputs();
  FigureOutputs(const FigureOutputs&) = delete;
  FigureOutputs& operator=(const FigureOutputs&) = delete;

  // The path of one of the names, as claimed.
  std::string path(const std::string& name) const;

 private:
  std::string directory_;
  bool made_directory_ = false;
  std::vector<std::unique_ptr<OutputClaim>> claims_;
};

}  // namespace rtiow

#pragma once
// The files a measurement command (bench, accuracy) writes into its --out directory, claimed
// before its minutes of work (core/io/output_claim.h): a second command aimed at the same
// files is refused at once rather than after its work, and every file is written through the
// claim's held directory. The directories the command made for them, left empty (it failed, or
// a signal ended it at once), are removed again: nothing is left that the user did not get.

#include <memory>
#include <string>
#include <vector>

namespace rtiow {

class OutputClaim;
class RemovedOnAbort;

class FigureOutputs {
 public:
  // Makes `directory` (and its missing parents) and claims each of `names` in it. `option`
  // names the directory in errors ("--out").
  FigureOutputs(const std::string& directory, const std::vector<std::string>& names,
                const std::string& option);
  ~FigureOutputs();
  FigureOutputs(const FigureOutputs&) = delete;
  FigureOutputs& operator=(const FigureOutputs&) = delete;

  // The path of one of the names, as claimed.
  std::string path(const std::string& name) const;

 private:
  // One directory this command made, with its parent held to remove it by name.
  struct MadeDirectory {
    std::string path;
    int parent_fd = -1;
    std::unique_ptr<RemovedOnAbort> on_abort;
  };
  void make_directories(const std::string& option);
  void remove_made_directories();  // deepest first; only those still empty

  std::string directory_;
  std::vector<MadeDirectory> made_;  // outermost first
  std::vector<std::unique_ptr<OutputClaim>> claims_;
};

}  // namespace rtiow

#include "app/mpi_launch.h"

#include <charconv>
#include <cstring>

namespace rtiow {
namespace {

// A launcher's count or index from the environment; -1 when absent or not a number.
long long number_in(const EnvironmentLookup& env, const char* name) {
  const char* text = env(name);
  if (!text) return -1;
  long long value = -1;
  const char* end = text + std::strlen(text);
  const auto [stop, error] = std::from_chars(text, end, value);
  return error == std::errc() && stop == end ? value : -1;
}

}  // namespace

std::string launch_refusal(bool built_with_mpi, const EnvironmentLookup& env) {
  if (built_with_mpi) return "";
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const long long processes = number_in(env, name);
    if (processes > 1) {
      return "started by an MPI launcher as one of " + std::to_string(processes) + " processes (" +
             name +
             "), but this rtiow was built without MPI: each would render the whole image. "
             "Run one process, or build with libopenmpi-dev installed (-DRTIOW_MPI=ON)";
    }
  }
  return "";
}

bool first_of_launch(const EnvironmentLookup& env) {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"}) {
    const long long rank = number_in(env, name);
    if (rank >= 0) return rank == 0;
  }
  return true;
}

}  // namespace rtiow

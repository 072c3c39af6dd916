#pragma once
// Whether this process may render where an MPI launcher started it. A build without MPI under
// `mpirun -np 2` would render the whole image in each process, and both would race for one
// output: it refuses in one line instead. The MPI facts `rtiow --version` prints.

#include <functional>
#include <string>

namespace rtiow {

// The environment as getenv reads it (a test gives its own).
using EnvironmentLookup = std::function<const char*(const char*)>;

// Empty where this process may go on; otherwise the error line: a build without MPI
// (`built_with_mpi` false) started by a launcher as one of several processes (Open MPI's
// OMPI_COMM_WORLD_SIZE, PMI's PMI_SIZE above 1).
std::string launch_refusal(bool built_with_mpi, const EnvironmentLookup& env);

// Whether this process is the launcher's first (or not under a launcher): the one that speaks
// for them all.
bool first_of_launch(const EnvironmentLookup& env);

}  // namespace rtiow

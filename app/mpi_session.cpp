#include "app/mpi_session.h"

#include <cstdlib>
#include <string>

#if defined(RTIOW_WITH_MPI)
#include <mpi.h>
#endif

namespace rtiow {

#if defined(RTIOW_WITH_MPI)
namespace {

// Launched by a process manager: OpenMPI's mpirun, or PMI/PMIx-based launchers (Slurm).
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"}) {
    if (std::getenv(v)) return true;
  }
  return false;
}

// Exact per-pixel sums (PixelSum, PixelSpread, FirstHitSum) add in any order to the same bits.
template <typename Exact>
void add_exact(void* in, void* inout, int* count, MPI_Datatype*) {
  auto* into = static_cast<Exact*>(inout);
  const auto* from = static_cast<const Exact*>(in);
  for (int i = 0; i < *count; ++i) into[i] += from[i];
}

// Adds every rank's `values` into rank 0's.
template <typename Exact>
void reduce_exact(int rank, std::vector<Exact>& values) {
  MPI_Datatype pixel;
  MPI_Type_contiguous(int(sizeof(Exact)), MPI_BYTE, &pixel);
  MPI_Type_commit(&pixel);
  MPI_Op add;
  MPI_Op_create(add_exact<Exact>, 1, &add);
  std::vector<Exact> total(rank == 0 ? values.size() : 0);
  // In slices: MPI counts are int, and a 4K film is 8M pixels of 48-96 bytes.
  constexpr std::size_t kSlice = 1 << 20;
  for (std::size_t begin = 0; begin < values.size(); begin += kSlice) {
    const int count = int(std::min(kSlice, values.size() - begin));
    MPI_Reduce(values.data() + begin, rank == 0 ? total.data() + begin : nullptr, count, pixel, add,
               0, MPI_COMM_WORLD);
  }
  if (rank == 0) values = std::move(total);
  MPI_Op_free(&add);
  MPI_Type_free(&pixel);
}

}  // namespace

std::string mpi_build_fact() {
  std::string fact = "MPI: ";
#if defined(OMPI_MAJOR_VERSION)
  fact += "Open MPI " + std::to_string(OMPI_MAJOR_VERSION) + "." +
          std::to_string(OMPI_MINOR_VERSION) + "." + std::to_string(OMPI_RELEASE_VERSION) + ", ";
#endif
  return fact + "the MPI " + std::to_string(MPI_VERSION) + "." + std::to_string(MPI_SUBVERSION) +
         " interface (rendering across ranks under mpirun)";
}

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  MPI_Init(&argc, &argv);
  initialized_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (initialized_) MPI_Finalize();
}

void MpiSession::reduce_sums(PixelSums& sums) const {
  if (!distributed()) return;
  sums.for_each_vector([&](auto& group) {
    if (!group.empty()) reduce_exact(rank_, group);
  });
}

std::uint64_t MpiSession::reduce_sum(std::uint64_t value) const {
  if (!distributed()) return value;
  std::uint64_t total = 0;
  MPI_Reduce(&value, &total, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  return total;
}

double MpiSession::reduce_max(double value) const {
  if (!distributed()) return value;
  double largest = 0;
  MPI_Reduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  return largest;
}

void MpiSession::abort(int code) const {
  if (initialized_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

#else

std::string mpi_build_fact() {
  return "MPI: not built in (build with libopenmpi-dev installed, or -DRTIOW_MPI=ON)";
}

MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
void MpiSession::reduce_sums(PixelSums&) const {}
std::uint64_t MpiSession::reduce_sum(std::uint64_t value) const {
  return value;
}
double MpiSession::reduce_max(double value) const {
  return value;
}
void MpiSession::abort(int code) const {
  std::exit(code);
}

#endif

}  // namespace rtiow

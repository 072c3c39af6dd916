#include "app/mpi_session.h"

#include <cstdlib>

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

void add_pixel_sums(void* in, void* inout, int* count, MPI_Datatype*) {
  add_sums(static_cast<PixelSum*>(inout), static_cast<const PixelSum*>(in), std::size_t(*count));
}

}  // namespace

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

void MpiSession::reduce_sums(std::vector<PixelSum>& sums) const {
  if (!distributed()) return;
  MPI_Datatype pixel;
  MPI_Type_contiguous(int(sizeof(PixelSum)), MPI_BYTE, &pixel);
  MPI_Type_commit(&pixel);
  MPI_Op add;
  MPI_Op_create(add_pixel_sums, 1, &add);
  std::vector<PixelSum> total(rank_ == 0 ? sums.size() : 0);
  // In slices: MPI counts are int, and a 4K film is 8M pixels of 48 bytes.
  constexpr std::size_t kSlice = 1 << 20;
  for (std::size_t begin = 0; begin < sums.size(); begin += kSlice) {
    const int count = int(std::min(kSlice, sums.size() - begin));
    MPI_Reduce(sums.data() + begin, rank_ == 0 ? total.data() + begin : nullptr, count, pixel, add,
               0, MPI_COMM_WORLD);
  }
  if (rank_ == 0) sums = std::move(total);
  MPI_Op_free(&add);
  MPI_Type_free(&pixel);
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

MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
void MpiSession::reduce_sums(std::vector<PixelSum>&) const {}
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

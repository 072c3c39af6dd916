#pragma once
// Rendering across MPI ranks (build option RTIOW_MPI). Every sample's randomness is keyed by
// (seed, pixel, sample), so rank r renders its share of the samples of every pixel, and the
// exact sums, added on rank 0, give the image one process would have given, bit for bit.
//
// Samples rather than tiles: every rank then traces the same pixels, so the cover's costly
// glass and cheap sky are shared evenly without any scheduling, and the only message is one
// reduction of the sums at the end (48 bytes per pixel from each rank; 144 with the spreads
// for --stats-channels, 112 more with --passes).

#include <cstdint>
#include <string>
#include <vector>

#include "core/film/pixel_sums.h"

namespace rtiow {

#if defined(RTIOW_WITH_MPI)
inline constexpr bool kBuiltWithMpi = true;
#else
inline constexpr bool kBuiltWithMpi = false;
#endif

// MPI as `rtiow --version` says it: the implementation and version built in, or that none is.
std::string mpi_build_fact();

class MpiSession {
 public:
  // Joins the MPI job when launched by mpirun (or another launcher); otherwise, or in a
  // build without MPI, a session of one rank that does nothing.
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool distributed() const { return size_ > 1; }

  // Adds every rank's sums, every group they keep, into rank 0's (the others' are left as they
  // were).
  void reduce_sums(PixelSums& sums) const;
  // Sum and maximum over ranks, delivered on rank 0.
  std::uint64_t reduce_sum(std::uint64_t value) const;
  double reduce_max(double value) const;

  // Ends every rank at once, with `code`: a failing rank must not leave the others waiting.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool initialized_ = false;
};

}  // namespace rtiow

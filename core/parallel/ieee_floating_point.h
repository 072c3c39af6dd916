#pragma once
// IEEE's default floating-point settings on the calling thread for a scope: denormals kept,
// neither flushed to zero nor read as zero (x86's MXCSR FTZ and DAZ bits). TBB runs an
// arena's tasks, and the thread that enters it, under the settings of the thread that started
// the arena; an Embree build that starts TBB leaves it flushing, and an application may set
// those bits on purpose (Embree recommends it). A scene's reading and a render must not
// depend on either: their arenas and task contexts are made under this guard.

#include <xmmintrin.h>

namespace rtiow {

class IeeeFloatingPoint {
 public:
  IeeeFloatingPoint() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ & ~kFlushBits); }
  ~IeeeFloatingPoint() { _mm_setcsr(saved_); }
  IeeeFloatingPoint(const IeeeFloatingPoint&) = delete;
  IeeeFloatingPoint& operator=(const IeeeFloatingPoint&) = delete;

 private:
  static constexpr unsigned kFlushBits = 0x8040;  // FTZ (bit 15) and DAZ (bit 6)
  unsigned saved_;
};

}  // namespace rtiow

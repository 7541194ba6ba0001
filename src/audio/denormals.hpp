#pragma once
// Flush-to-zero and denormals-are-zero for the audio thread: a decaying envelope walks
// into the subnormal range after ~1 s, where x86 arithmetic becomes ~100× slower.
// Scoped: the previous floating-point mode is restored on exit.
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define MALLET_HAS_MXCSR 1
#endif

namespace mallet::audio {

class ScopedFlushDenormals {
 public:
  ScopedFlushDenormals() {
#ifdef MALLET_HAS_MXCSR
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
#endif
  }
  ~ScopedFlushDenormals() {
#ifdef MALLET_HAS_MXCSR
    _mm_setcsr(saved_);
#endif
  }
  ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
  ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;

  //! Whether FTZ and DAZ are on for the calling thread now.
  static bool active() {
#ifdef MALLET_HAS_MXCSR
    return (_mm_getcsr() & (kFlushToZero | kDenormalsAreZero)) == (kFlushToZero | kDenormalsAreZero);
#else
    return false;
#endif
  }

 private:
  static constexpr unsigned kFlushToZero = 0x8000;
  static constexpr unsigned kDenormalsAreZero = 0x0040;
  unsigned saved_ = 0;
};

}  // namespace mallet::audio

// Rendering runs with denormal floats flushed to zero (the SSE control
// register's FTZ and DAZ bits), as Embree and Cycles advise: a denormal
// operand costs a microcode assist of a hundred cycles or more, and they
// arise where no value of a picture needs them, e.g. in the unused lanes
// of a packed division GCC makes of a Vec3 divided by a float, whose
// contents are whatever the stack held.
//
// The bits are per thread: each stretch of rendering work (a tile, an
// explained sample) sets them and restores the caller's on leaving, so
// that loaders, tests and the Python host keep IEEE behaviour, and a
// render and its `explain` compute alike, bit for bit.
#pragma once

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace sombra {

class DenormalsFlushed {
public:
#if defined(__SSE__) || defined(_M_X64)
    DenormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
    ~DenormalsFlushed() { _mm_setcsr(saved_); }
#else
    DenormalsFlushed() = default;
#endif
    DenormalsFlushed(const DenormalsFlushed&) = delete;
    DenormalsFlushed& operator=(const DenormalsFlushed&) = delete;

private:
#if defined(__SSE__) || defined(_M_X64)
    static constexpr unsigned kFlushToZero = 0x8000;       // results that would be denormal are 0
    static constexpr unsigned kDenormalsAreZero = 0x0040;  // denormal operands are read as 0
    unsigned saved_;
#endif
};

}  // namespace sombra

// The guard rendering work runs under (core/flush_denormals.h): inside it a
// denormal operand reads as zero and a denormal result is flushed to zero;
// after it the thread computes with IEEE denormals again.
#include "core/flush_denormals.h"

#include <gtest/gtest.h>

#include <limits>

namespace sombra {
namespace {

TEST(DenormalsFlushed, FlushesInsideAndRestoresTheCallersModeAfter) {
#if !(defined(__SSE__) || defined(_M_X64))
    GTEST_SKIP() << "no SSE control register on this machine: the guard does nothing";
#endif
    volatile float tiny = std::numeric_limits<float>::denorm_min() * 1000.0f;  // a denormal
    volatile float smallest_normal = std::numeric_limits<float>::min();
    ASSERT_GT(tiny, 0.0f);
    {
        const DenormalsFlushed flushed;
        EXPECT_EQ(tiny * 1.0f, 0.0f);             // denormal operand read as zero
        EXPECT_EQ(smallest_normal * 0.5f, 0.0f);  // denormal result flushed
        const DenormalsFlushed nested;            // nesting keeps the mode
        EXPECT_EQ(tiny + 0.0f, 0.0f);
    }
    EXPECT_EQ(tiny * 1.0f, tiny);
    EXPECT_GT(smallest_normal * 0.5f, 0.0f);
}

}  // namespace
}  // namespace sombra

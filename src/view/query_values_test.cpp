#include "view/query_values.h"

#include <gtest/gtest.h>

namespace sombra {
namespace {

TEST(QueryValues, ReadsWholeFiniteNumbers) {
    std::string problem;
    EXPECT_EQ(parse_query_number("fov", "45.5", problem), 45.5);
    EXPECT_EQ(parse_query_number("fov", "-1e3", problem), -1000.0);
    for (const char* bad : {"", "nan", "inf", "-inf", "1e40", "45deg", " 45", "0x10", "1,2"}) {
        problem.clear();
        EXPECT_FALSE(parse_query_number("fov", bad, problem)) << bad;
        EXPECT_NE(problem.find("fov must be a finite number"), std::string::npos) << problem;
    }
}

TEST(QueryValues, ReadsIntegersInRange) {
    std::string problem;
    EXPECT_EQ(parse_query_int("spp", "16", 1, 64, problem), 16);
    for (const char* bad : {"0", "65", "-1", "1.5", "", "99999999999999999999", "16 "}) {
        problem.clear();
        EXPECT_FALSE(parse_query_int("spp", bad, 1, 64, problem)) << bad;
        EXPECT_NE(problem.find("spp must be an integer from 1 to 64"), std::string::npos) << problem;
    }
}

TEST(QueryValues, ReadsThreeNumbers) {
    std::string problem;
    const std::optional<Vec3> v = parse_query_vec3("origin", "1,-2.5,3e1", problem);
    ASSERT_TRUE(v) << problem;
    EXPECT_EQ(v->x, 1.0f);
    EXPECT_EQ(v->y, -2.5f);
    EXPECT_EQ(v->z, 30.0f);
    for (const char* bad : {"1,2", "1,2,3,4", "1,,3", "1,2,nan", "", ",,", "1;2;3"}) {
        problem.clear();
        EXPECT_FALSE(parse_query_vec3("origin", bad, problem)) << bad;
        EXPECT_EQ(problem.rfind("origin must be", 0), 0u) << problem;
    }
    // A long bad value is cut in the message.
    problem.clear();
    EXPECT_FALSE(parse_query_vec3("origin", std::string(10000, 'x'), problem));
    EXPECT_LT(problem.size(), 200u);
}

}  // namespace
}  // namespace sombra

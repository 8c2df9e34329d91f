// Path tracing sees instanced emitters as their flattened copies (spec §23):
// the same radiance over the floor of render/instanced_emitters_test_util.h's
// lamps, by z-tests of independent runs against their sample variances, and
// about the same noise, since next-event estimation now samples the
// instances' emitters too (before, only BSDF sampling found them).
#include <gtest/gtest.h>

#include <cmath>

#include "render/instanced_emitters_test_util.h"
#include "render/path_test_util.h"

namespace sombra {
namespace {

using testing::Estimate;
using testing::kZ;
using testing::PathRun;

struct Totals {
    double variance_instanced = 0, variance_flattened = 0, variance_bsdf_only = 0;
};

// One floor point seen from just above (below every lamp), depth 3.
void compare_at(const Scene& instanced, const Scene& flattened, Vec3 x, std::uint64_t seed, int channel,
                Totals& totals) {
    const Vec3 eye = x + Vec3{0.01f, 0.3f, 0.02f};
    const int n = 4000;
    // Independent seeds: the two runs would otherwise follow nearly the same paths.
    const Estimate a = PathRun{instanced, 3}.estimate(eye, x, n, seed, channel);
    const Estimate b = PathRun{flattened, 3}.estimate(eye, x, n, seed + 1000, channel);
    const double se = std::sqrt(a.standard_error() * a.standard_error() + b.standard_error() * b.standard_error());
    ASSERT_GT(se, 0.0);
    EXPECT_LT(std::fabs(a.mean() - b.mean()) / se, kZ)
        << "at " << x.x << " " << x.z << " channel " << channel << ": instanced " << a.mean() << " ± "
        << a.standard_error() << ", flattened " << b.mean() << " ± " << b.standard_error();
    totals.variance_instanced += a.standard_error() * a.standard_error();
    totals.variance_flattened += b.standard_error() * b.standard_error();
    const Estimate c = PathRun{instanced, 3, LightStrategy::BsdfOnly}.estimate(eye, x, n, seed + 2000, channel);
    totals.variance_bsdf_only += c.standard_error() * c.standard_error();
}

TEST(InstancedEmittersPath, FloorRadianceAgreesWithFlattenedCopiesAndIsAsQuiet) {
    const Scene instanced = testing::instanced_lamps();
    const Scene flattened = testing::flattened_lamps();
    Totals totals;
    std::uint64_t seed = 70;
    for (const Vec3 x : {Vec3{0, 0, 0}, Vec3{0.8f, 0, -0.9f}, Vec3{-0.7f, 0, -1.2f}, Vec3{0.3f, 0, 1.3f},
                         Vec3{-1.5f, 0, -0.3f}, Vec3{1.6f, 0, -1.6f}, Vec3{-1.9f, 0, 1.7f}, Vec3{1.2f, 0, 0.6f}})
        for (const int channel : {0, 2}) compare_at(instanced, flattened, x, ++seed, channel, totals);
    // Same estimator, same lights: the noise is comparable (the summed
    // variances' ratio, whose own sampling error at 16 × 4000 samples is
    // a few per cent). BSDF sampling alone, the strategy instanced
    // emitters had before, is far noisier: the check can tell.
    const double ratio = std::sqrt(totals.variance_instanced / totals.variance_flattened);
    EXPECT_LT(ratio, 1.25) << "standard error instanced / flattened";
    EXPECT_GT(ratio, 1 / 1.25) << "standard error instanced / flattened";
    EXPECT_GT(std::sqrt(totals.variance_bsdf_only / totals.variance_flattened), 2.0)
        << "BSDF sampling alone should be much noisier";
}

TEST(InstancedEmittersPath, DirectIntegratorSeesInstancedEmittersAsFlattenedCopies) {
    // The direct integrator only sees emission (spec §4): each lamp's
    // emitting faces from below, where the one-sided ones shine unless mirrored upside down.
    const Scene instanced = testing::instanced_lamps();
    const Scene flattened = testing::flattened_lamps();
    const Accel ai = make_accel(instanced, AccelKind::Bvh), af = make_accel(flattened, AccelKind::Bvh);
    const LightSet li = make_light_set(instanced, make_constant_environment(Vec3{0.0f}), false);
    const LightSet lf = make_light_set(flattened, make_constant_environment(Vec3{0.0f}), false);
    const IntegratorContext ci{&instanced, &ai, &li, 1, LightStrategy::Mis};
    const IntegratorContext cf{&flattened, &af, &lf, 1, LightStrategy::Mis};
    int lit = 0;
    const std::vector<Transform> placements = testing::lamp_placements();
    for (const Transform& t : placements)
        for (const Vec3 local : {Vec3{0.05f, -0.05f, 0.05f}, Vec3{-0.1f, 0, 0.15f}}) {
            // Up from the floor towards a point of the lamp's one-sided triangle, then its quad.
            const Vec3 target = transform_point(t, local);
            const Ray ray{{target.x + 0.01f, 0.05f, target.z - 0.02f},
                          target - Vec3{target.x + 0.01f, 0.05f, target.z - 0.02f}};
            RayCounters counters;
            const Vec3 a = trace_direct(ci, ray, counters), b = trace_direct(cf, ray, counters);
            EXPECT_EQ(a, b) << "towards " << target.x << " " << target.y << " " << target.z;
            lit += max_component(a) > 0.0f;
        }
    EXPECT_GT(lit, 12);
}

}  // namespace
}  // namespace sombra

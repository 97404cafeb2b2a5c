// The analytic fields' surfaces are what their documentation says.
#include "octrace/build/AnalyticField.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace octrace;

namespace {

/// Sizes (in samples) of the 6-connected components of the samples with value >= 0.
std::vector<std::size_t> insideComponents(const ScalarField& f) {
    std::vector<char> seen(f.values.size(), 0);
    std::vector<std::size_t> sizes;
    std::vector<ivec3> stack;
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) {
                if (seen[f.index(i, j, k)] || !(f.values[f.index(i, j, k)] >= 0.0f)) continue;
                std::size_t n = 0;
                stack.push_back({i, j, k});
                seen[f.index(i, j, k)] = 1;
                while (!stack.empty()) {
                    const ivec3 c = stack.back();
                    stack.pop_back();
                    ++n;
                    for (int a = 0; a < 3; ++a)
                        for (int s : {-1, 1}) {
                            ivec3 q = c;
                            q[a] += s;
                            if (q[a] < 0 || q[a] >= f.dims[a]) continue;
                            const std::size_t idx = f.index(q.x, q.y, q.z);
                            if (seen[idx] || !(f.values[idx] >= 0.0f)) continue;
                            seen[idx] = 1;
                            stack.push_back(q);
                        }
                }
                sizes.push_back(n);
            }
    return sizes;
}

}  // namespace

TEST(AnalyticField, SpheresAreSixtyDisjointBallsOfDifferentSizes) {
    // 129 samples: spacing 1/64 < the 0.02 gap between balls, so no two balls share a
    // component, and every ball (radius >= 0.04) holds samples.
    const ScalarField f = makeAnalyticField("spheres", 129);
    std::vector<std::size_t> sizes = insideComponents(f);
    ASSERT_EQ(sizes.size(), 60u);
    std::sort(sizes.begin(), sizes.end());
    // Radii 0.04 to 0.3: volumes of a few hundred to about 100,000 samples; the drawn radii
    // span more than a factor 3 (volume 27).
    EXPECT_GT(sizes.back(), 27 * sizes.front());
    // Inside [-1,1]^3: no ball touches the grid's faces.
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i : {0, f.dims.x - 1}) {
                EXPECT_LT(f.values[f.index(i, j, k)], 0.0f);
                EXPECT_LT(f.values[f.index(j, i, k)], 0.0f);
                EXPECT_LT(f.values[f.index(j, k, i)], 0.0f);
            }
}

TEST(AnalyticField, SpheresFollowTheSeed) {
    const ScalarField a = makeAnalyticField("spheres", 33, 1), b = makeAnalyticField("spheres", 33, 1);
    const ScalarField c = makeAnalyticField("spheres", 33, 2);
    EXPECT_EQ(a.values, b.values);
    EXPECT_NE(a.values, c.values);
    EXPECT_EQ(a.source, "analytic:spheres(seed 1)");
}

TEST(AnalyticField, NamesEveryFieldItMakes) {
    for (const std::string& name : analyticFieldNames()) EXPECT_NO_THROW(makeAnalyticField(name, 5)) << name;
    EXPECT_EQ(analyticFieldList(), "sphere, torus, gyroid, noise, spheres");
    EXPECT_THROW(makeAnalyticField("cube", 5), UsageError);
}

// The memory budget: the helpers of util/Memory.h, estimateBuildMemory against the octrees it
// estimates, and buildShellOctree refusing (up front) or stopping (while building) a build
// that does not fit its budget.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

using namespace octrace;

namespace {

std::string limitMessage(const ScalarField& f, const BuildOptions& o) {
    try {
        buildShellOctree(f, o);
    } catch (const LimitError& e) {
        return e.what();
    }
    return "(no LimitError)";
}

/// 129^3 samples of 1 over [-1,1]^3 with a -1 at every odd (i,j,k): the octrees of depth 6 and
/// less, whose voxel corners all fall on even samples, see no surface at all; depth 7 finds 8
/// voxels around each of the 262,144 spikes. The estimate, which extrapolates depth 6, misses them.
ScalarField spikes() {
    ScalarField f = makeAnalyticField("sphere", 129);
    f.name = "spikes";
    for (int k = 0; k < 129; ++k)
        for (int j = 0; j < 129; ++j)
            for (int i = 0; i < 129; ++i) f.values[f.index(i, j, k)] = (i % 2 && j % 2 && k % 2) ? -1.0f : 1.0f;
    return f;
}

}  // namespace

TEST(Memory, FormatsBytesInBinaryUnits) {
    EXPECT_EQ(formatBytes(0), "0 bytes");
    EXPECT_EQ(formatBytes(1), "1 byte");
    EXPECT_EQ(formatBytes(1023), "1023 bytes");
    EXPECT_EQ(formatBytes(1024), "1 KiB");
    EXPECT_EQ(formatBytes(1536), "1.5 KiB");
    EXPECT_EQ(formatBytes(std::uint64_t(38) << 20), "38 MiB");
    EXPECT_EQ(formatBytes(std::uint64_t(700) << 20), "700 MiB");
    EXPECT_EQ(formatBytes(std::uint64_t(3) << 29), "1.5 GiB");
    EXPECT_EQ(formatBytes(std::numeric_limits<std::uint64_t>::max()), "16 EiB");
}

TEST(Memory, MultipliesSizesWithoutWrappingAround) {
    EXPECT_EQ(saturatingMultiply(3, 5), 15u);
    EXPECT_EQ(saturatingMultiply(std::uint64_t(1) << 40, std::uint64_t(1) << 40), std::numeric_limits<std::uint64_t>::max());
    EXPECT_EQ(saturatingMultiply(0, std::numeric_limits<std::uint64_t>::max()), 0u);
}

TEST(Memory, TheDefaultBudgetIsHalfThePhysicalMemory) {
    const std::uint64_t physical = physicalMemoryBytes();
    ASSERT_GT(physical, std::uint64_t(64) << 20) << "cannot read the physical memory on this machine";
    EXPECT_EQ(defaultMemoryBudget(), physical / 100 * kDefaultMemoryBudgetPercent);
    EXPECT_EQ(kDefaultMemoryBudgetPercent, 50);
}

TEST(Memory, ACheckOverTheBudgetNamesTheNeedAndTheBudget) {
    EXPECT_NO_THROW(checkMemoryBudget("x", 100, 100));
    EXPECT_NO_THROW(checkMemoryBudget("x", std::uint64_t(1) << 50, 0));  // 0: no limit
    try {
        checkMemoryBudget("f.nrrd: reading 4000x4000x4000 float samples", std::uint64_t(9) << 30, std::uint64_t(1) << 30);
        FAIL() << "no exception";
    } catch (const LimitError& e) {
        EXPECT_STREQ(e.what(), "f.nrrd: reading 4000x4000x4000 float samples needs about 9 GiB, more than the memory "
                               "budget of 1 GiB (`max_memory`)");
    }
}

TEST(BuildMemory, CountsTheFieldAndTheSamplerExactly) {
    const ScalarField f = makeAnalyticField("sphere", 33);
    const auto est = estimateBuildMemory(f, 0.0, 3);
    ASSERT_EQ(est.size(), 3u);
    const std::uint64_t samples = 33 * 33 * 33;
    // Pyramid levels 17^3, 9^3, 5^3, 3^3, 2^3, 1: a min and a max float and a masked byte each.
    const std::uint64_t pyramid = 9 * (17 * 17 * 17 + 9 * 9 * 9 + 5 * 5 * 5 + 3 * 3 * 3 + 2 * 2 * 2 + 1);
    for (int d = 1; d <= 3; ++d) {
        const BuildMemoryEstimate& e = est[std::size_t(d) - 1];
        EXPECT_EQ(e.depth, d);
        EXPECT_EQ(e.fieldBytes, f.values.capacity() * sizeof(float));
        EXPECT_EQ(e.samplerBytes, samples * sizeof(float) + pyramid + 3 * ((1u << d) + 1) * 16) << d;
        EXPECT_EQ(e.total(), e.fieldBytes + e.samplerBytes + e.octreeBytes);
    }
}

// Up to depth 6 the voxels are counted; deeper they are extrapolated. On the analytic fields
// the extrapolation stays above the truth and within 60 % of it (1.25 is the margin).
TEST(BuildMemory, EstimatesExactlyToDepthSixAndSomewhatAboveTheTruthDeeper) {
    for (const char* name : {"sphere", "gyroid", "noise"}) {
        const ScalarField f = makeAnalyticField(name, 65);
        const auto est = estimateBuildMemory(f, 0.0, 8, 2);
        for (int d = 1; d <= 8; ++d) {
            BuildOptions o;
            o.depth = d;
            o.threads = 2;
            const Octree t = buildShellOctree(f, o);
            const double v = double(t.boundaryVoxels()), e = est[std::size_t(d) - 1].boundaryVoxels;
            if (d <= 6) {
                EXPECT_EQ(e, v) << name << " depth " << d;
            } else {
                EXPECT_GE(e, v) << name << " depth " << d;
                EXPECT_LE(e, 1.6 * v) << name << " depth " << d;
            }
            // The estimate holds the subtrees and the joined octree: twice the octree's bytes.
            EXPECT_GE(double(est[std::size_t(d) - 1].octreeBytes), 1.9 * double(t.bytes()) * (d <= 6 ? 1.0 : 1.2))
                << name << " depth " << d;
        }
    }
}

TEST(BuildMemory, RefusesADepthOverTheBudgetNamingTheLargestDepthThatFits) {
    const ScalarField f = makeAnalyticField("sphere", 65);
    const auto est = estimateBuildMemory(f, 0.0, 9);
    BuildOptions o;
    o.depth = 9;
    o.memoryBudget = (est[7].total() + est[8].total()) / 2;
    const std::string m = limitMessage(f, o);
    EXPECT_EQ(m.rfind("analytic:sphere: the octree of 'sphere' at depth 9 needs about " + formatBytes(est[8].total()) +
                          " (field 1 MiB, sampler ",
                      0),
              0u)
        << m;
    EXPECT_NE(m.find("boundary voxels), more than the memory budget of " + formatBytes(o.memoryBudget) +
                     " (`max_memory`); the largest depth that fits is 8 (about " + formatBytes(est[7].total()) + ")"),
              std::string::npos)
        << m;
    // That depth builds within the same budget, and the budget does not change the octree.
    o.depth = 8;
    const Octree withBudget = buildShellOctree(f, o);
    o.memoryBudget = 0;
    const Octree without = buildShellOctree(f, o);
    EXPECT_EQ(withBudget.nodes().size(), without.nodes().size());
    ASSERT_EQ(withBudget.voxels().size(), without.voxels().size());
    EXPECT_EQ(0, std::memcmp(withBudget.nodes().data(), without.nodes().data(), without.nodes().size() * sizeof(OctreeNode)));
    EXPECT_EQ(0, std::memcmp(withBudget.voxels().data(), without.voxels().data(), without.voxels().size() * sizeof(Voxel)));
}

// Smooth surfaces store 8 bytes of corner values per boundary voxel (BuildOptions::corners),
// sampled from a list of the voxels' cells: the estimate counts both, and a budget that holds
// the voxel octree but not its corners refuses the smooth build and lets the voxel build through.
TEST(BuildMemory, CountsTheCornerValuesOfSmoothSurfaces) {
    const ScalarField f = makeAnalyticField("sphere", 65);
    BuildOptions o;
    o.depth = 8;
    o.threads = 2;
    const auto voxel = estimateBuildMemory(f, o);
    o.corners = true;
    const auto smooth = estimateBuildMemory(f, o);
    ASSERT_EQ(voxel.size(), smooth.size());
    for (std::size_t i = 0; i < smooth.size(); ++i) {
        EXPECT_EQ(voxel[i].attributeBytes, 0u);
        EXPECT_EQ(smooth[i].octreeBytes, voxel[i].octreeBytes);
        EXPECT_EQ(smooth[i].attributeBytes, std::uint64_t(smooth[i].boundaryVoxels * (8 + 12))) << i;
    }
    // Exact to depth 6: the corner bytes of the octree built there.
    o.depth = 6;
    const Octree t6 = buildShellOctree(f, o);
    EXPECT_EQ(smooth[5].attributeBytes, t6.corners().size() * (8 + 12));
    // The volume form has no corners (the caps have no crossing to find).
    o.depth = 8;
    o.form = OctreeForm::Volume;
    EXPECT_EQ(estimateBuildMemory(f, o).back().attributeBytes, 0u);
    o.form = OctreeForm::Shell;

    o.memoryBudget = (voxel.back().total() + smooth.back().total()) / 2;
    const std::string m = limitMessage(f, o);
    EXPECT_NE(m.find("at depth 8 needs about " + formatBytes(smooth.back().total())), std::string::npos) << m;
    EXPECT_NE(m.find(", per-voxel attributes " + formatBytes(smooth.back().attributeBytes) + " for about"), std::string::npos) << m;
    o.corners = false;
    EXPECT_EQ(limitMessage(f, o), "(no LimitError)");
}

TEST(BuildMemory, RefusesEveryDepthWhenTheFieldAndItsSamplerAloneDoNotFit) {
    const ScalarField f = makeAnalyticField("torus", 33);
    BuildOptions o;
    o.memoryBudget = 100 * 1024;
    EXPECT_EQ(limitMessage(f, o), "analytic:torus: building the octree of 'torus' needs more than the memory budget of "
                                  "100 KiB (`max_memory`) at any depth: the field and the sampler alone need about 332 KiB");
}

// The running check: a surface that only appears deeper than the probes makes the estimate
// far too low, and the build stops with a message at the allocation that would go over.
TEST(BuildMemory, StopsCleanlyWhenTheBuildGoesOverTheBudgetItsEstimateMissed) {
    const ScalarField f = spikes();
    const auto est = estimateBuildMemory(f, 0.0, 8);
    EXPECT_LT(est[7].boundaryVoxels, 1000.0);  // the probes saw nothing
    for (int threads : {1, 2}) {
        BuildOptions o;
        o.depth = 8;
        o.threads = threads;
        o.memoryBudget = est[7].total() + (std::uint64_t(1) << 20);
        EXPECT_EQ(limitMessage(f, o).rfind("analytic:sphere: building the octree of 'spikes' at depth 8 stopped before going "
                                           "over the memory budget of " + formatBytes(o.memoryBudget) +
                                           " (`max_memory`; it was estimated at " + formatBytes(est[7].total()) +
                                           "); try a smaller `depth` or a larger `max_memory`",
                                           0),
                  0u)
            << limitMessage(f, o);
    }
    // With room, the same build succeeds: 8 voxels around each spike at depth 7.
    BuildOptions o;
    o.depth = 7;
    EXPECT_EQ(buildShellOctree(f, o).boundaryVoxels(), 64u * 64u * 64u * 8u);
}

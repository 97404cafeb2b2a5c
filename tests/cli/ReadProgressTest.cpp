// Reading an input is a stage of model::buildSurface's progress before the build, and the
// same cancellation stops it (issue 26): the hooks the studio and the CLI give a build.
#include "CliRunner.h"

#include "octrace/model/Surface.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

using namespace octrace;
using octrace::testcli::haveShared;
using octrace::testcli::sharedData;

namespace {

// What the hooks saw, in order: ('r', f) for the read's progress, ('b', f) for the build's
// (from the builder's threads, hence the lock).
struct Seen {
    std::mutex lock;
    std::vector<std::pair<char, double>> calls;
    int cancelAfterReads = -1;  // cancel once this many read reports came (never when negative)

    int reads() {
        int n = 0;
        for (const auto& c : calls) n += c.first == 'r';
        return n;
    }
    model::BuildHooks hooks() {
        model::BuildHooks h;
        h.readProgress = [this](double f) {
            std::lock_guard<std::mutex> g(lock);
            calls.push_back({'r', f});
        };
        h.progress = [this](double f) {
            std::lock_guard<std::mutex> g(lock);
            calls.push_back({'b', f});
        };
        h.cancelled = [this] {
            std::lock_guard<std::mutex> g(lock);
            return cancelAfterReads >= 0 && reads() >= cancelAfterReads;
        };
        return h;
    }
};

// The XA10 fMRI series as DICOM (the folder) and as dcm2niix's 4-D NIfTI of it.
const char* const kXa10Files[] = {"", "/reference_dcm2niix.nii"};

model::SurfaceSpec xa10Volume(int volume, const std::string& file) {
    model::SurfaceSpec a;
    a.input = sharedData("medical/siemens_xa10_fmri_4d") + file;
    a.request.volume = volume;
    a.depth = 7;  // auto's choice: the six slices span 14 mm of a 213 mm cube
    a.iso = 200.0;  // in the brain's signal (the volumes hold 0 .. about 1200)
    a.threads = 1;
    return a;
}

}  // namespace

TEST(SurfaceBuild, ReadingReportsItsOwnProgressToOneBeforeTheBuildStarts) {
    if (!haveShared("medical/siemens_xa10_fmri_4d")) GTEST_SKIP() << "shared data absent";
    for (const std::string file : kXa10Files) {
        SCOPED_TRACE(file.empty() ? "DICOM" : "NIfTI");
        const model::SurfaceSpec a = xa10Volume(1, file);
        Seen seen;
        const model::Surface s = model::buildSurface(a, seen.hooks());
        EXPECT_GT(s.report.boundaryVoxels, 0u);
        ASSERT_FALSE(seen.calls.empty());
        std::size_t firstBuild = seen.calls.size();
        for (std::size_t i = 0; i < seen.calls.size(); ++i)
            if (seen.calls[i].first == 'b') {
                firstBuild = i;
                break;
            }
        ASSERT_GT(firstBuild, 1u) << "the read reported nothing before the build";
        ASSERT_LT(firstBuild, seen.calls.size()) << "the build reported nothing";
        for (std::size_t i = 0; i < firstBuild; ++i) {
            EXPECT_EQ(seen.calls[i].first, 'r') << i;
            if (i > 0) {
                EXPECT_LE(seen.calls[i - 1].second, seen.calls[i].second) << i;
            }
        }
        EXPECT_EQ(seen.calls[firstBuild - 1].second, 1.0);
        for (std::size_t i = firstBuild; i < seen.calls.size(); ++i) EXPECT_EQ(seen.calls[i].first, 'b') << "read reported after the build began";
    }
}

TEST(SurfaceBuild, CancellingDuringTheReadStopsItWithCancelledErrorBeforeAnyBuild) {
    if (!haveShared("medical/siemens_xa10_fmri_4d")) GTEST_SKIP() << "shared data absent";
    for (const std::string file : kXa10Files) {
        SCOPED_TRACE(file.empty() ? "DICOM" : "NIfTI");
        const model::SurfaceSpec a = xa10Volume(3, file);
        Seen seen;
        seen.cancelAfterReads = 2;
        EXPECT_THROW(model::buildSurface(a, seen.hooks()), CancelledError);
        EXPECT_EQ(seen.reads(), 2);
        for (const auto& c : seen.calls) EXPECT_EQ(c.first, 'r') << "the build ran after the read was cancelled";
        // The field alone (the studio's read stage) stops the same way.
        Seen alone;
        alone.cancelAfterReads = 1;
        model::Surface s;
        EXPECT_THROW(model::readSurfaceField(a, s, alone.hooks()), CancelledError);
        EXPECT_EQ(alone.reads(), 1);
    }
}

// What the studio's slice panes take from the slice model (app/studio/SliceViews.*): the world
// to sample mapping of the crosshair and probe, the values a slice keeps for the probe, the
// percentile window, and the figure's direction names.
#include "octrace/model/Slice.h"

#include "octrace/render/SliceView.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace octrace;

namespace {

/// A patient volume 6 x 5 x 4, rows along -y, an uneven z axis, v = 100 i + 10 j + k.
ScalarField patientVolume() {
    ScalarField f;
    f.name = "v";
    f.patientLps = true;
    f.dims = ivec3(6, 5, 4);
    f.origin = dvec3(-3.0, 7.0, 11.0);
    f.spacing = dvec3(0.8, 1.25, 1.0);
    f.direction = dmat3(dvec3(1.0, 0.0, 0.0), dvec3(0.0, -1.0, 0.0), dvec3(0.0, 0.0, 1.0));
    f.coords[2] = {0.0, 2.0, 2.5, 6.0};
    f.values.resize(f.sampleCount());
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 6; ++i) f.values[f.index(i, j, k)] = float(100 * i + 10 * j + k);
    return f;
}

}  // namespace

TEST(SliceProbe, GridPositionInvertsWorldFromGridOnTurnedAndUnevenAxes) {
    const ScalarField f = patientVolume();
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 6; ++i) {
                const dvec3 g = sliceGridPosition(f, f.worldFromGrid(i, j, k));
                EXPECT_NEAR(g.x, i, 1e-12);
                EXPECT_NEAR(g.y, j, 1e-12);
                EXPECT_NEAR(g.z, k, 1e-12);
            }
    // Between samples: fractions of the step of that interval (z: 2.5 .. 6 mm).
    const dvec3 g = sliceGridPosition(f, f.origin + dvec3(0.4, -0.625, 2.5 + 0.25 * 3.5));
    EXPECT_NEAR(g.x, 0.5, 1e-12);
    EXPECT_NEAR(g.y, 0.5, 1e-12);
    EXPECT_NEAR(g.z, 2.25, 1e-12);
}

TEST(SliceProbe, TheSliceKeepsTheValuesOfItsPixels) {
    const ScalarField f = patientVolume();
    model::SliceSpec spec;
    spec.input = "test";
    spec.plane = SlicePlane::Axial;
    spec.index = 2;
    spec.width = 40;
    spec.height = 30;
    const model::SliceResult r = model::renderSlice(f, spec);
    ASSERT_EQ(r.values.width, 40);
    ASSERT_EQ(r.values.height, 30);
    const SliceValues again = sampleSlice(f, r.view);
    ASSERT_EQ(r.values.values.size(), again.values.size());
    int valid = 0;
    for (std::size_t p = 0; p < again.values.size(); ++p) {
        ASSERT_EQ(r.values.state[p], again.state[p]);
        if (again.state[p] != SliceSample::Valid) continue;
        ++valid;
        EXPECT_EQ(r.values.values[p], again.values[p]);
        // The value of the field (linear here: trilinear is exact) at the pixel's world position
        // (within half a sample outside the grid: the edge's).
        const int x = int(p % 40), y = int(p / 40);
        const dvec3 g = sliceGridPosition(f, r.view.world(x, y));
        EXPECT_NEAR(r.values.values[p], 100.0 * std::clamp(g.x, 0.0, 5.0) + 10.0 * std::clamp(g.y, 0.0, 4.0) + 2.0, 1e-3);
    }
    EXPECT_GT(valid, 300);
}

TEST(SliceProbe, QuantileWindowSpansThePercentilesOfTheValidValues) {
    ScalarField f;
    f.name = "mr";
    f.dims = ivec3(10, 10, 2);
    f.values.resize(f.sampleCount());
    f.valid.assign(f.sampleCount(), 1);
    // 0 .. 99 twice, and a masked outlier that must not count.
    for (std::size_t i = 0; i < f.values.size(); ++i) f.values[i] = float(i % 100);
    f.values[7] = 1e6f;
    f.valid[7] = 0;
    const ValueWindow w = model::quantileWindow(f, 0.01, 0.99);
    // 199 valid values sorted: ranks round(0.01 * 198) = 2 and round(0.99 * 198) = 196.
    EXPECT_DOUBLE_EQ(w.centre, 0.5 * (1.0 + 98.0));
    EXPECT_DOUBLE_EQ(w.width, 97.0);
    f.valid.assign(f.sampleCount(), 0);
    EXPECT_THROW(model::quantileWindow(f), EmptyResultError);
}

TEST(SliceProbe, DirectionNamesAreTheFiguresLetters) {
    ScalarField f = patientVolume();
    EXPECT_EQ(model::sliceDirectionName(f, sliceScreenRight(SlicePlane::Axial)), "L");
    EXPECT_EQ(model::sliceDirectionName(f, sliceScreenUp(SlicePlane::Axial)), "A");
    EXPECT_EQ(model::sliceDirectionName(f, sliceScreenRight(SlicePlane::Sagittal)), "P");
    EXPECT_EQ(model::sliceDirectionName(f, -sliceScreenUp(SlicePlane::Coronal)), "I");
    f.patientLps = false;
    EXPECT_EQ(model::sliceDirectionName(f, sliceScreenUp(SlicePlane::Z)), "+y");
}

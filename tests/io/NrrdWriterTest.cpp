#include "IoTestSupport.h"

#include "octrace/io/NrrdReader.h"
#include "octrace/io/NrrdWriter.h"
#include "octrace/util/Error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>

using namespace octrace;

namespace {

// 17 x 11 x 7 samples, value = a function of the index that no axis swap or flip preserves.
ScalarField makeField() {
    ScalarField f;
    f.name = "density";
    f.units = "g/cm3";
    f.dims = ivec3(17, 11, 7);
    f.origin = dvec3(-12.5, 300.25, 7.125);
    f.spacing = dvec3(0.5, 1.25, 3.0);
    // Rotation by 30 degrees about (1,2,3): every column has three non-zero components.
    f.direction = dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(30.0), glm::normalize(dvec3(1, 2, 3))));
    f.values.resize(f.sampleCount());
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 11; ++j)
            for (int i = 0; i < 17; ++i) f.values[f.index(i, j, k)] = float(i + 100 * j + 10000 * k) * 0.5f;
    return f;
}

}  // namespace

TEST(NrrdWriter, RoundTripKeepsValuesAndRotatedAnisotropicGeometry) {
    test::TempDir dir;
    ScalarField out = makeField();
    io::NrrdWriter::write(out, dir.file("rotated.nrrd"));
    ScalarField in = io::NrrdReader::read(dir.file("rotated.nrrd"));

    EXPECT_EQ(in.name, "density");
    EXPECT_EQ(in.units, "g/cm3");
    EXPECT_EQ(in.dims, out.dims);
    ASSERT_EQ(in.values, out.values);
    EXPECT_TRUE(in.valid.empty());
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(in.origin[a], out.origin[a], 1e-12);
        EXPECT_NEAR(in.spacing[a], out.spacing[a], 1e-12);
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(in.direction[a][r], out.direction[a][r], 1e-12);
    }
    // The far corner lands where the original field puts it.
    dvec3 p = in.worldFromGrid(16, 10, 6), q = out.worldFromGrid(16, 10, 6);
    EXPECT_NEAR(glm::length(p - q), 0.0, 1e-9);
}

TEST(NrrdWriter, InvalidSamplesComeBackInvalid) {
    test::TempDir dir;
    ScalarField out = makeField();
    out.valid.assign(out.sampleCount(), 1);
    out.valid[out.index(3, 4, 5)] = 0;
    io::NrrdWriter::write(out, dir.file("masked.nrrd"));
    ScalarField in = io::NrrdReader::read(dir.file("masked.nrrd"));
    ASSERT_EQ(in.valid.size(), in.sampleCount());
    EXPECT_FALSE(in.isValid(in.index(3, 4, 5)));
    EXPECT_EQ(in.validCount(), in.sampleCount() - 1);
}

TEST(NrrdWriter, EvenRectilinearAxisIsStoredAsSpacing) {
    test::TempDir dir;
    ScalarField out = makeField();
    out.direction = dmat3(1.0);
    out.coords[2] = {10, 12, 14, 16, 18, 20, 22};
    io::NrrdWriter::write(out, dir.file("even.nrrd"));
    ScalarField in = io::NrrdReader::read(dir.file("even.nrrd"));
    EXPECT_NEAR(in.spacing.z, 2.0, 1e-12);
    EXPECT_NEAR(in.worldFromGrid(0, 0, 6).z, out.worldFromGrid(0, 0, 6).z, 1e-9);
}

TEST(NrrdWriter, RefusesUnevenRectilinearAxisAndLeavesNoFile) {
    test::TempDir dir;
    ScalarField out = makeField();
    out.coords[2] = {0, 1, 2, 4, 8, 16, 32};
    EXPECT_THROW_WITH(io::NrrdWriter::write(out, dir.file("uneven.nrrd")), OutputError, "uneven axis 2");
    EXPECT_FALSE(std::filesystem::exists(dir.file("uneven.nrrd")));
}

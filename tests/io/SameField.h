#pragma once
// The same field from two paths (a file and memory, a NetCDF file and a Zarr store), shared by
// the io tests.
#include "octrace/build/ScalarField.h"

#include <gtest/gtest.h>

#include <cstring>

namespace octrace::test {

// Bit for bit: the same floats (compared as bytes), mask, geometry, mapping, names and notes.
inline void expectSameField(const ScalarField& file, const ScalarField& memory) {
    EXPECT_EQ(memory.name, file.name);
    EXPECT_EQ(memory.units, file.units);
    EXPECT_EQ(memory.standardName, file.standardName);
    EXPECT_EQ(memory.dims, file.dims);
    EXPECT_EQ(memory.origin, file.origin);
    EXPECT_EQ(memory.spacing, file.spacing);
    EXPECT_EQ(memory.direction, file.direction);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(memory.coords[std::size_t(a)], file.coords[std::size_t(a)]) << a;
    ASSERT_EQ(memory.values.size(), file.values.size());
    EXPECT_EQ(std::memcmp(memory.values.data(), file.values.data(), file.values.size() * sizeof(float)), 0);
    EXPECT_EQ(memory.valid, file.valid);
    EXPECT_EQ(memory.geographic.valid, file.geographic.valid);
    EXPECT_EQ(memory.geographic.lon0, file.geographic.lon0);
    EXPECT_EQ(memory.geographic.lat0, file.geographic.lat0);
    EXPECT_EQ(memory.geographic.verticalScale, file.geographic.verticalScale);
    EXPECT_EQ(memory.notes, file.notes);
    EXPECT_EQ(memory.window.centre, file.window.centre);
    EXPECT_EQ(memory.window.width, file.window.width);
}

}  // namespace octrace::test

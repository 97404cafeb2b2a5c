#pragma once
// Checks shared by the volume-form and CSG tests.
#include "octrace/build/Volume.h"

#include <gtest/gtest.h>

namespace octrace {

/// The invariant of Volume.h, by brute force over every cell: a voxel of the solid with a face
/// neighbour outside the solid (or outside the cube) is a boundary voxel.
inline void expectClosed(const Octree& t) {
    const int n = 1 << t.depth;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
                if (cellState(t, {x, y, z}) != CellState::Interior) continue;
                for (int a = 0; a < 3; ++a)
                    for (int s = -1; s <= 1; s += 2) {
                        ivec3 nb(x, y, z);
                        nb[a] += s;
                        ASSERT_NE(cellState(t, nb), CellState::Empty) << x << "," << y << "," << z << " axis " << a;
                    }
            }
}

/// Two octrees with the same cube, depth, structure and normals.
inline void expectSameOctree(const Octree& a, const Octree& b) {
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.cubeOrigin, b.cubeOrigin);
    EXPECT_EQ(a.cubeSide, b.cubeSide);
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    ASSERT_EQ(a.voxels().size(), b.voxels().size());
    for (std::size_t i = 0; i < a.nodes().size(); ++i) {
        ASSERT_EQ(a.nodes()[i].childMask, b.nodes()[i].childMask) << i;
        ASSERT_EQ(a.nodes()[i].termMask, b.nodes()[i].termMask) << i;
        if (a.nodes()[i].childMask) {
            ASSERT_EQ(a.nodes()[i].firstChild, b.nodes()[i].firstChild) << i;
        }
    }
    for (std::size_t i = 0; i < a.voxels().size(); ++i) ASSERT_EQ(a.voxels()[i].normal, b.voxels()[i].normal) << i;
}

}  // namespace octrace

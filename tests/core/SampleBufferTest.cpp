// A field's samples read in place from another owner's memory (Python's NumPy arrays): reading
// never copies, writing copies first and never changes the owner's memory, copies share the
// borrow and keep the owner alive, and an octree built from borrowed samples equals one built
// from owned ones.
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/SampleBuffer.h"
#include "octrace/build/ScalarField.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

using namespace octrace;

namespace {

std::shared_ptr<std::vector<float>> owner(std::vector<float> v) { return std::make_shared<std::vector<float>>(std::move(v)); }

SampleBuffer borrowOf(const std::shared_ptr<std::vector<float>>& o) { return SampleBuffer::borrow(o->data(), o->size(), o); }

}  // namespace

TEST(SampleBuffer, ReadsInPlaceWithoutACopy) {
    const auto o = owner({1, 2, 3, 4});
    const SampleBuffer b = borrowOf(o);
    EXPECT_TRUE(b.borrowed());
    EXPECT_EQ(b.data(), o->data());
    EXPECT_EQ(b.size(), 4u);
    EXPECT_EQ(b[2], 3.0f);
    EXPECT_EQ(b.back(), 4.0f);
    float sum = 0;
    for (float v : b) sum += v;
    EXPECT_EQ(sum, 10.0f);
    EXPECT_EQ(b.span().data(), o->data());
}

TEST(SampleBuffer, WritingCopiesFirstAndLeavesTheOwnersMemory) {
    const auto o = owner({1, 2, 3});
    SampleBuffer b = borrowOf(o);
    b[1] = 20.0f;  // non-const access: copy on write
    EXPECT_FALSE(b.borrowed());
    EXPECT_NE(b.data(), o->data());
    EXPECT_EQ((*o)[1], 2.0f);
    EXPECT_EQ(b[0], 1.0f);
    EXPECT_EQ(b[1], 20.0f);
    EXPECT_EQ(b[2], 3.0f);

    SampleBuffer c = borrowOf(o);
    c.resize(5, 9.0f);
    EXPECT_EQ(c.size(), 5u);
    EXPECT_EQ(c[2], 3.0f);
    EXPECT_EQ(c[4], 9.0f);
    EXPECT_EQ(o->size(), 3u);

    SampleBuffer d = borrowOf(o);
    d.assign(d.begin() + 1, d.begin() + 3);  // from its own borrowed samples (a const read first)
    EXPECT_EQ(d, (SampleBuffer{2, 3}));
    d = std::vector<float>{7};
    EXPECT_FALSE(d.borrowed());
    EXPECT_EQ(d.size(), 1u);
}

TEST(SampleBuffer, CopiesShareTheBorrowAndKeepTheOwnerAlive) {
    std::weak_ptr<std::vector<float>> watch;
    SampleBuffer copy;
    {
        auto o = owner({5, 6});
        watch = o;
        const SampleBuffer b = borrowOf(o);
        copy = b;
        EXPECT_EQ(std::as_const(copy).data(), b.data());  // read through const: no copy
    }
    ASSERT_FALSE(watch.expired());  // the copy holds the owner
    EXPECT_EQ(std::as_const(copy)[1], 6.0f);
    EXPECT_TRUE(copy.borrowed());
    EXPECT_EQ(copy[1], 6.0f);  // a non-const read is a write's access: the samples are copied
    EXPECT_FALSE(copy.borrowed());
    EXPECT_TRUE(watch.expired());
    copy.clear();
    EXPECT_TRUE(copy.empty());
}

TEST(SampleBuffer, AFieldOfBorrowedSamplesBuildsTheSameOctreeWithoutCopying) {
    const int n = 20;
    auto samples = std::make_shared<std::vector<float>>();
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double x = i - 9.5, y = j - 9.5, z = k - 9.5;
                samples->push_back(float(std::sqrt(x * x + y * y + z * z)));
            }
    const auto fieldOf = [&](SampleBuffer values) {
        ScalarField f;
        f.name = "r";
        f.source = "test";
        f.dims = ivec3(n);
        f.values = std::move(values);
        return f;
    };
    const ScalarField owned = fieldOf(SampleBuffer(*samples));
    const ScalarField borrowed = fieldOf(borrowOf(samples));
    const ScalarField shared = borrowed.copy();
    EXPECT_EQ(shared.values.data(), samples->data());  // ScalarField::copy shares borrowed samples
    BuildOptions o{5, 6.0, 2};
    const Octree a = buildOctree(owned, o), b = buildOctree(borrowed, o);
    EXPECT_TRUE(borrowed.values.borrowed());  // the builder only read them
    EXPECT_EQ(a.voxels().size(), b.voxels().size());
    EXPECT_GT(a.voxels().size(), 0u);
    EXPECT_EQ(a.nodes().size(), b.nodes().size());
}

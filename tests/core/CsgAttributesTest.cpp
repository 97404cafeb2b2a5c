// What CSG keeps of each voxel besides its normal: the field's values (a CT's window grey on
// the cut faces, as 3D Slicer shows them) and per-voxel colours; the shell keeps both.
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/csg/Csg.h"
#include "octrace/render/Shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace octrace;

namespace {

/// A CT-like head: HU = 1000 (0.7 - r) + 300 x over [-1,1]^3 (soft tissue falling off outward
/// with a gradient across), 65 samples per axis.
double hu(const dvec3& p) { return 1000.0 * (0.7 - glm::length(p)) + 300.0 * p.x; }

ScalarField ctLike() {
    ScalarField f;
    f.name = "ct";
    f.units = "HU";
    f.source = "ct-like";
    f.dims = ivec3(65);
    f.origin = dvec3(-1.0);
    f.spacing = dvec3(2.0 / 64);
    for (int k = 0; k < 65; ++k)
        for (int j = 0; j < 65; ++j)
            for (int i = 0; i < 65; ++i) f.values.push_back(float(hu(f.origin + dvec3(i, j, k) * f.spacing)));
    return f;
}

Octree volumeWithValues(const ScalarField& f, int depth) {
    BuildOptions o{depth, 0.0, 0};
    o.form = OctreeForm::Volume;
    o.voxelValues = true;
    return buildOctree(f, o);
}

const Solid kWedge = parseSolid("box:0,0,0,2,2,2");

}  // namespace

TEST(CsgAttributes, CutFacesOfAFieldShowItsWindowGreyThere) {
    const ScalarField f = ctLike();
    const Octree ct = volumeWithValues(f, 7);
    Octree cut = csg(CsgOperand::of(ct), CsgOp::Difference, CsgOperand::of(kWedge));
    ASSERT_EQ(cut.voxelValues().size(), cut.voxels().size());
    // Voxels the operation left as they were keep their values exactly.
    std::size_t same = 0;
    cut.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        std::uint32_t w;
        if (cellState(cut, c) != CellState::Boundary || cellState(ct, c, &w) != CellState::Boundary) return;
        if (decodeNormal(cut.voxels()[v].normal) != decodeNormal(ct.voxels()[w].normal)) return;
        EXPECT_EQ(cut.voxelValues()[v], ct.voxelValues()[w]);
        ++same;
    });
    EXPECT_GT(same, 10000u);
    // With the field at hand (as --cut has it), the cut faces take its values where they are.
    fillVoxelValues(cut, f);
    RenderSettings settings;
    settings.window = ValueWindow{300.0, 800.0};
    const Albedo albedo(cut, settings);
    const double h = cut.voxelSize();
    std::size_t faces = 0;
    double worstGrey = 0.0;
    cut.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        const dvec3 centre = cut.cubeOrigin + (dvec3(c) + 0.5) * h;
        const dvec3 n(decodeNormal(cut.voxels()[v].normal));
        // Cut-face voxels: on the wedge's faces, well inside the head, facing into the wedge;
        // not near the centre, where the field's cone tip makes trilinear sampling differ
        // from hu() by several HU.
        const double r = glm::length(centre);
        if (cellState(cut, c) != CellState::Boundary || r < 0.2 || r > 0.5 || std::max({n.x, n.y, n.z}) < 0.999) return;
        const double expected = hu(centre - n * h);  // one voxel in from the face, as the build samples
        EXPECT_NEAR(cut.voxelValues()[v], expected, 1.0) << c.x << "," << c.y << "," << c.z;
        const float grey = settings.window.grey(float(expected), false);
        const vec3 shown = albedo.at(v, float(c.z) + 0.5f);
        const float linear = grey <= 0.04045f ? grey / 12.92f : std::pow((grey + 0.055f) / 1.055f, 2.4f);
        worstGrey = std::max(worstGrey, double(std::abs(shown.r - linear)));
        ++faces;
    });
    EXPECT_GT(faces, 1000u);
    EXPECT_LT(worstGrey, 0.005);
    RecordProperty("cut_face_voxels", std::to_string(faces));
    RecordProperty("worst_grey_error", std::to_string(worstGrey));
    // The shell keeps them.
    const Octree shell = extractShell(cut);
    EXPECT_EQ(shell.voxelValues().size(), shell.voxels().size());
}

TEST(CsgAttributes, ColoursSurviveOperationsAndCutFacesTakeTheNearestOnes) {
    const ScalarField f = ctLike();
    Octree ct = volumeWithValues(f, 6);
    ct.setVoxelValues({});
    // A colour per voxel slot from its position: red by x, green by y, blue by z.
    std::vector<std::uint32_t> colours(ct.voxels().size());
    ct.forEachVoxel([&](const ivec3& c, std::uint32_t v) { colours[v] = packColour(vec3(c) / 63.0f); });
    ct.setColours(std::move(colours));
    const std::set<std::uint32_t> palette(ct.colours().begin(), ct.colours().end());
    for (CsgOp op : {CsgOp::Difference, CsgOp::Intersection, CsgOp::Union}) {
        const Octree r = csg(CsgOperand::of(ct), op, CsgOperand::of(kWedge));
        ASSERT_TRUE(r.hasColours()) << csgOpName(op);
        EXPECT_TRUE(r.voxelValues().empty());
        std::size_t kept = 0;
        r.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
            std::uint32_t w;
            if (cellState(r, c) == CellState::Boundary && cellState(ct, c, &w) == CellState::Boundary) {
                EXPECT_EQ(r.colours()[v], ct.colours()[w]);
                ++kept;
            }
            // A voxel of the solid alone (union) has no colour to take but its neighbours'.
            EXPECT_TRUE(palette.count(r.colours()[v])) << csgOpName(op) << " " << c.x << "," << c.y << "," << c.z;
        });
        EXPECT_GT(kept, 500u) << csgOpName(op);
        EXPECT_TRUE(extractShell(r).hasColours());
    }
    // A subtracted octree gives nothing: its colours do not reach the result.
    const Octree big = volumeWithValues(f, 6);
    const Octree d = csg(CsgOperand::of(big), CsgOp::Difference, CsgOperand::of(ct));
    EXPECT_FALSE(d.hasColours());
}

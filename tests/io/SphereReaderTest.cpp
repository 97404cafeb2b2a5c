// Molecule files as sphere scenes: PDB and mmCIF atoms, Bondi radii, element colours, models
// and alternate locations, the messages for broken files, the limit before allocation.
#include "IoTestSupport.h"

#include "octrace/build/OctreeBuilder.h"
#include "octrace/io/SphereReader.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/scene/Spheres.h"
#include "octrace/util/Error.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

using namespace octrace;
using octrace::test::TempDir;

namespace {

/// One PDB ATOM/HETATM record in the fixed columns of the format.
std::string atom(int serial, const char* name, double x, double y, double z, const char* element, const char* record = "ATOM  ",
                 char alt = ' ') {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%-6s%5d %-4s%cGLY A   1    %8.3f%8.3f%8.3f  1.00 20.00          %2s", record, serial, name, alt, x,
                  y, z, element);
    return buf;
}

const char* kCif = R"(data_TEST
# a comment
loop_
_atom_site.group_PDB
_atom_site.id
_atom_site.type_symbol
_atom_site.label_atom_id
_atom_site.label_alt_id
_atom_site.Cartn_x
_atom_site.Cartn_y
_atom_site.Cartn_z
_atom_site.pdbx_PDB_model_num
ATOM 1 N N . 1.000 2.000 3.000 1
ATOM 2 C "C A" . 2.5 -2 0.25 1
HETATM 3 Fe FE . 4 4 4 1
ATOM 4 O O . 9 9 9 2
loop_
_other.text
;a text field
spanning lines
;
)";

}  // namespace

TEST(SphereReader, ReadsPdbAtomsWithBondiRadiiAndElementColours) {
    const std::string text = atom(1, "N", 1, 2, 3, "N") + "\n" + atom(2, "CA", 2.5, -2, 0.25, "C") + "\n" +
                             atom(3, "FE", 4, 4, 4, "FE", "HETATM") + "\nEND\n";
    SphereSet s = io::parseMolecule(text, "t.pdb");
    ASSERT_EQ(s.spheres.size(), 3u);
    EXPECT_EQ(s.units, "angstrom");
    EXPECT_EQ(s.name, "t");
    EXPECT_DOUBLE_EQ(s.spheres[0].radius, 1.55);  // Bondi: N
    EXPECT_DOUBLE_EQ(s.spheres[1].radius, 1.70);  // C
    EXPECT_DOUBLE_EQ(s.spheres[2].radius, 2.0);   // Fe: not in Bondi, the documented fallback
    EXPECT_EQ(s.spheres[1].centre, dvec3(2.5, -2.0, 0.25));
    EXPECT_GT(s.spheres[0].colour.b, s.spheres[0].colour.r);  // nitrogen blue
    bool noted = false;
    for (const auto& n : s.notes) noted = noted || n.find("not in Bondi 1964) for: FE") != std::string::npos;
    EXPECT_TRUE(noted);
}

TEST(SphereReader, BondiTableAndFallback) {
    bool known = false;
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("O", &known), 1.52);
    EXPECT_TRUE(known);
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("cl", &known), 1.75);
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("H"), 1.20);
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("S"), 1.80);
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("Fe", &known), 2.0);
    EXPECT_FALSE(known);
    EXPECT_DOUBLE_EQ(io::vanDerWaalsRadius("Xx", &known), 2.0);
    EXPECT_FALSE(known);
    EXPECT_EQ(io::elementColour("O"), io::elementColour("o"));
    EXPECT_NE(io::elementColour("O"), io::elementColour("C"));
}

TEST(SphereReader, CifGivesTheSameSpheresAsPdb) {
    const std::string pdb = atom(1, "N", 1, 2, 3, "N") + "\n" + atom(2, "CA", 2.5, -2, 0.25, "C") + "\n" +
                            atom(3, "FE", 4, 4, 4, "FE", "HETATM") + "\n";
    SphereSet a = io::parseMolecule(pdb, "a.pdb"), b = io::parseMolecule(kCif, "a.cif");
    ASSERT_EQ(b.spheres.size(), 3u);  // model 2 left out
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(a.spheres[i].centre, b.spheres[i].centre) << i;
        EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius) << i;
        EXPECT_EQ(a.spheres[i].colour, b.spheres[i].colour) << i;
    }
}

TEST(SphereReader, ReadsOnlyTheFirstModelAndTheFirstAlternateLocation) {
    const std::string text = "MODEL        1\n" + atom(1, "CA", 0, 0, 0, "C", "ATOM  ", 'A') + "\n" +
                             atom(2, "CA", 0.3, 0, 0, "C", "ATOM  ", 'B') + "\n" + atom(3, "N", 1, 0, 0, "N") +
                             "\nENDMDL\nMODEL        2\n" + atom(1, "CA", 5, 5, 5, "C") + "\nENDMDL\n";
    SphereSet s = io::parseMolecule(text, "m.pdb");
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_EQ(s.spheres[0].centre.x, 0.0);
    EXPECT_EQ(s.spheres[1].centre.x, 1.0);
}

TEST(SphereReader, TakesTheElementFromTheAtomNameWhenItsColumnsAreBlank) {
    // Columns 77-78 absent: " CA " is carbon (alpha), "FE  " iron, " OG " oxygen.
    std::string a = atom(1, " CA", 0, 0, 0, "").substr(0, 54), b = atom(2, "FE", 1, 1, 1, "").substr(0, 54),
                c = atom(3, " OG", 2, 2, 2, "").substr(0, 54);
    SphereSet s = io::parseMolecule(a + "\n" + b + "\n" + c + "\n", "e.pdb");
    ASSERT_EQ(s.spheres.size(), 3u);
    EXPECT_DOUBLE_EQ(s.spheres[0].radius, 1.70);
    EXPECT_EQ(s.spheres[1].colour, io::elementColour("Fe"));
    EXPECT_DOUBLE_EQ(s.spheres[2].radius, 1.52);
}

TEST(SphereReader, BrokenFilesGiveOneLineNamingTheLineAndField) {
    EXPECT_THROW_WITH(io::parseMolecule("", "e.pdb"), FileError, "e.pdb: file is empty (0 bytes)");
    EXPECT_THROW_WITH(io::parseMolecule("HEADER nothing\nEND\n", "n.pdb"), FileError, "n.pdb: no atoms (no ATOM or HETATM record)");
    std::string bad = atom(1, "CA", 0, 0, 0, "C");
    bad.replace(38, 8, "  nan   ");
    EXPECT_THROW_WITH(io::parseMolecule("REMARK\n" + bad + "\n", "b.pdb"), FileError,
                      "b.pdb: line 2: ATOM record: coordinate y (columns 39-46) '  nan   ' is not a finite number");
    EXPECT_THROW_WITH(io::parseMolecule("ATOM      1  CA  GLY A   1       1.000\n", "s.pdb"), FileError,
                      "s.pdb: line 1: ATOM record is 38 characters long, its coordinates end at column 54");
    EXPECT_THROW_WITH(io::parseMolecule("data_X\nloop_\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n1 2 3 4\n", "r.cif"),
                      FileError, "r.cif: line 6: the _atom_site loop ends inside a row (1 of 3 values)");
    EXPECT_THROW_WITH(io::parseMolecule("data_X\nloop_\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n1 2 'x\n", "q.cif"),
                      FileError, "q.cif: line 6: quoted value not closed on its line");
    EXPECT_THROW_WITH(io::parseMolecule("data_X\nloop_\n_atom_site.type_symbol\n_atom_site.Cartn_x\n_atom_site.Cartn_y\nC 1 2\n", "m.cif"),
                      FileError, "m.cif: the _atom_site category has no Cartn_z item");
    EXPECT_THROW_WITH(io::parseMolecule("data_X\n_entry.id X\n", "z.cif"), FileError, "z.cif: no atoms (no _atom_site rows)");
    std::string far = atom(1, "CA", 0, 0, 0, "C");
    far.replace(30, 8, "   1e300");
    EXPECT_THROW_WITH(io::parseMolecule(far + "\n", "f.pdb"), FileError, "f.pdb: line 1: atom coordinates beyond the supported");
}

TEST(SphereReader, RefusesAtomsBeyondTheMemoryBudgetBeforeAllocating) {
    std::string text;
    for (int i = 0; i < 1000; ++i) text += atom(i + 1, "CA", i, 0, 0, "C") + "\n";
    EXPECT_THROW_WITH(io::parseMolecule(text, "big.pdb", 1000 * 16), LimitError, "big.pdb: 1000 atoms");
    EXPECT_EQ(io::parseMolecule(text, "big.pdb", 1 << 20).spheres.size(), 1000u);
}

TEST(SphereReader, ReadsFilesAndNamesMissingOnes) {
    TempDir dir;
    {
        std::ofstream f(dir.file("x.cif"), std::ios::binary);
        f << kCif;
    }
    EXPECT_EQ(io::readMolecule(dir.file("x.cif")).spheres.size(), 3u);
    EXPECT_THROW_WITH(io::readMolecule(dir.file("none.pdb")), InputError, "none.pdb: no such file");
    EXPECT_TRUE(io::isMoleculeFile("a/B.PDB"));
    EXPECT_TRUE(io::isMoleculeFile("x.mmcif"));
    EXPECT_FALSE(io::isMoleculeFile("x.nrrd"));
}

TEST(SphereReader, ReadsHaemoglobin) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "molecule/4HHB.pdb");
    SphereSet s = io::readMolecule(path);
    ASSERT_EQ(s.spheres.size(), 4779u);  // 4,384 ATOM + 395 HETATM (data/README.md)
    std::map<double, std::size_t> radii;
    for (const Sphere& sp : s.spheres) ++radii[sp.radius];
    EXPECT_EQ(radii[1.70], 2954u);  // carbon
    EXPECT_EQ(radii[1.55], 780u);   // nitrogen
    EXPECT_EQ(radii[1.52], 1027u);  // oxygen
    EXPECT_EQ(radii[1.80], 14u);    // sulphur and phosphorus
    EXPECT_EQ(radii[2.0], 4u);      // the four haem irons
    // The first atom: ATOM 1 N VAL A 1 at (6.204, 16.869, 4.854).
    EXPECT_EQ(s.spheres[0].centre, dvec3(6.204, 16.869, 4.854));
}

TEST(SphereReader, HaemoglobinVoxelsKeepTheirAtomsElementColours) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "molecule/4HHB.pdb");
    const SphereSet s = io::readMolecule(path);
    const Octree t = buildShellOctree(sphereDistanceField(s, (1 << 6) + 5), {6, 0.0, 0});
    const std::vector<std::uint32_t> colours = sphereColoursAtVoxels(t, s);
    ASSERT_EQ(colours.size(), t.voxels().size());
    // Against every atom in turn (no buckets): the atom whose surface is nearest the voxel's
    // centre gives its CPK colour; count the voxels of oxygen, nitrogen, carbon and sulphur.
    const std::uint32_t oxygen = packColour({1.0f, 13 / 255.0f, 13 / 255.0f});  // Jmol CPK O: 255,13,13
    std::map<std::uint32_t, std::size_t> byColour;
    const double h = t.voxelSize();
    std::size_t checked = 0;
    t.forEachVoxel([&](const ivec3& cell, std::uint32_t v) {
        if (v % 7 != 0) return;  // a seventh of the voxels keeps the brute force quick
        const dvec3 p = t.cubeOrigin + (dvec3(cell) + 0.5) * h;
        double best = INFINITY;
        std::size_t atom = 0;
        for (std::size_t i = 0; i < s.spheres.size(); ++i) {
            const double d = glm::length(p - s.spheres[i].centre) - s.spheres[i].radius;
            if (d < best) best = d, atom = i;
        }
        const vec3 c = s.spheres[atom].colour;
        ASSERT_EQ(colours[v], packColour(vec3(linearToSrgb8(c.r), linearToSrgb8(c.g), linearToSrgb8(c.b)) / 255.0f)) << "voxel " << v;
        ++byColour[colours[v]];
        ++checked;
    });
    EXPECT_GT(checked, 1000u);
    EXPECT_GE(byColour.size(), 4u);  // C, N, O, S at least
    EXPECT_GT(byColour[oxygen], checked / 10);
}

// CityJSON through io::readCityModel: transform, levels of detail, CRS, broken files, and the
// real Delft file of ../shared/data/city.
#include "CityJson.h"
#include "IoTestSupport.h"
#include "octrace/io/CityReader.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace octrace;
using namespace octrace::io;
using octrace::test::testData;

namespace {
const std::string kCube = testData("city/cube.city.json");

std::string cubeText() {
    std::ifstream in(kCube);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

TEST(CityReader, ReadsCityJsonWithItsTransformAndHighestLod) {
    const CityModel m = readCityModel(kCube);
    EXPECT_EQ(m.crs, "EPSG:28992");
    ASSERT_EQ(m.objects.size(), 2u);
    EXPECT_EQ(m.objectCount(CityRole::Solid), 1u);
    EXPECT_EQ(m.objectCount(CityRole::Terrain), 1u);
    const Box3 b = m.bounds();
    EXPECT_NEAR(b.lo.x, 990.0, 1e-9);
    EXPECT_NEAR(b.hi.x, 1020.0, 1e-9);
    EXPECT_NEAR(b.lo.z, 5.0, 1e-9);
    EXPECT_NEAR(b.hi.z, 20.0, 1e-9);  // the LoD 2.2 roof's apex: 1500 * 0.01 + 5
}

TEST(CityReader, LodSelectChoosesTheLevelAndAPrefixTakesItsSublevels) {
    CityRequest r;
    r.lod = "1";
    const CityModel lod1 = readCityModel(kCube, r);
    EXPECT_NEAR(lod1.bounds().hi.z, 15.0, 1e-9);  // the LoD 1 block
    EXPECT_TRUE(lod1.notes.empty()) << lod1.notes.front();  // its shell is closed
    r.lod = "2";
    const CityModel lod2 = readCityModel(kCube, r);
    EXPECT_NEAR(lod2.bounds().hi.z, 20.0, 1e-9);
    ASSERT_EQ(lod2.objects.size(), 1u);  // the ground has no LoD 2: left out and said
    ASSERT_EQ(lod2.notes.size(), 1u);
    EXPECT_NE(lod2.notes[0].find("1 objects without a geometry of LoD 2, left out (ground)"), std::string::npos) << lod2.notes[0];
    r.lod = "3";
    EXPECT_THROW_WITH(readCityModel(kCube, r), EmptyResultError, "no object has a geometry of LoD 3");
}

TEST(CityReader, ReprojectsIntoTheRequestedCrs) {
    CityRequest r;
    r.crs = "EPSG:32631";  // UTM 31N: Amersfoort's false origin lies far south-west of the Netherlands
    const CityModel m = readCityModel(kCube, r);
    EXPECT_EQ(m.crs, "EPSG:32631");
    const Box3 b = m.bounds();
    EXPECT_GT(b.lo.y, 5.0e6);  // northings in the millions of metres
    EXPECT_NEAR(b.hi.z - b.lo.z, 15.0, 0.5);
    EXPECT_NEAR(b.hi.x - b.lo.x, 30.0, 1.5);  // sizes kept (the box turns by the grids' convergence)
}

TEST(CityReader, AWrongCrsIsAClearError) {
    CityRequest r;
    r.crs = "EPSG:999999";
    EXPECT_THROW_WITH(readCityModel(kCube, r), InputError, "--crs: unknown coordinate reference system 'EPSG:999999'");
    r.crs = "EPSG:4326";
    EXPECT_THROW_WITH(readCityModel(kCube, r), InputError, "not a projected CRS");
}

TEST(CityReader, BrokenFilesAreToldApartFromOtherFormats) {
    EXPECT_THROW_WITH(detail::parseCityJson("{\"type\": \"FeatureCollection\"}", "a.json", ""), FormatNotSupported, "a.json: not CityJSON");
    EXPECT_THROW_WITH(detail::parseCityJson("{\"type\": \"CityJSON\", ", "b.json", ""), FileError, "b.json: not valid JSON");
    std::string text = cubeText();
    text.replace(text.find("[[9, 10, 11]]"), 13, "[[9, 10, 99]]");
    EXPECT_THROW_WITH(detail::parseCityJson(text, "c.json", ""), FileError,
                      "c.json: object 'ground': vertex index 99 out of range (the file has 13 vertices)");
    EXPECT_THROW_WITH(readCityModel(testData("city/absent.json")), InputError, "no such file");
}

TEST(CityReader, ReadsDelftWithTerrainAndBuildingsAndSaysWhatItCouldNotUse) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/delft.json");
    const CityModel m = readCityModel(path);
    EXPECT_EQ(m.crs, "EPSG:7415");
    std::size_t buildings = 0;
    for (const auto& o : m.objects) buildings += o.type == "Building";
    EXPECT_EQ(buildings, 160u);
    EXPECT_EQ(m.objectCount(CityRole::Terrain), 407u);
    EXPECT_GT(m.triangles.size(), 30000u);
    bool open = false;
    for (const auto& n : m.notes) open = open || n.find("solids with an open shell") != std::string::npos;
    EXPECT_TRUE(open);
    const std::string info = describeCityInput(path);
    EXPECT_NE(info.find("crs: EPSG:7415"), std::string::npos) << info;
    EXPECT_NE(info.find("Building: 160"), std::string::npos) << info;
}

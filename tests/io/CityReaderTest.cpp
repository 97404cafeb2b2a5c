// CityJSON through io::readCityModel: transform, levels of detail, CRS, broken files, and the
// real Delft file of ../shared/data/city.
#include "../FileBytes.h"
#include "city/CityGml.h"
#include "city/CityJson.h"
#include "city/CityScene.h"
#include "IoTestSupport.h"
#include "octrace/build/CityVoxelizer.h"
#include "octrace/io/CityReader.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <fstream>

using namespace octrace;
using namespace octrace::io;
using octrace::test::testData;

namespace {
const std::string kCube = testData("city/cube.city.json");

std::string cubeText() {
    return testutil::fileBytes(kCube);
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
    EXPECT_THROW_WITH(readCityModel(kCube, r), InputError, "`crs`: unknown coordinate reference system 'EPSG:999999'");
    r.crs = "EPSG:4326";
    EXPECT_THROW_WITH(readCityModel(kCube, r), InputError, "not a projected CRS");
}

TEST(CityReader, BrokenFilesAreToldApartFromOtherFormats) {
    EXPECT_THROW_WITH(io::detail::parseCityJson("{\"type\": \"FeatureCollection\"}", "a.json", ""), FormatNotSupported, "a.json: not CityJSON");
    EXPECT_THROW_WITH(io::detail::parseCityJson("{\"type\": \"CityJSON\", ", "b.json", ""), FileError, "b.json: not valid JSON");
    // Found by fuzz_cityjson (long run of 2026-11-25): a number beyond double's range is not a
    // syntax error to nlohmann::json but out_of_range, which escaped as std::terminate.
    EXPECT_THROW_WITH(io::detail::parseCityJson("{\"type\": \"CityJSON\", \"transform\": [0.012e992]}", "d.json", ""),
                      FileError, "d.json: not valid JSON ([json.exception.out_of_range.406] number overflow");
    std::string text = cubeText();
    text.replace(text.find("[[9, 10, 11]]"), 13, "[[9, 10, 99]]");
    EXPECT_THROW_WITH(io::detail::parseCityJson(text, "c.json", ""), FileError,
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

namespace {
/// A 2 x 1 RGB GeoTIFF in longitude/latitude over [lon0, lon1] x [lat0, lat1]: west half red,
/// east half blue.
void writeTwoColourTiff(const std::string& path, double lon0, double lon1, double lat0, double lat1) {
    GDALAllRegister();
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    ASSERT_NE(gtiff, nullptr);
    GDALDataset* ds = gtiff->Create(path.c_str(), 2, 1, 3, GDT_Byte, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {lon0, (lon1 - lon0) / 2, 0, lat1, 0, -(lat1 - lat0)};
    ds->SetGeoTransform(gt);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    ds->SetSpatialRef(&wgs84);
    const std::uint8_t r[2] = {255, 0}, g[2] = {0, 0}, b[2] = {0, 255};
    const std::uint8_t* planes[3] = {r, g, b};
    for (int k = 0; k < 3; ++k)
        ASSERT_EQ(ds->GetRasterBand(k + 1)->RasterIO(GF_Write, 0, 0, 2, 1, const_cast<std::uint8_t*>(planes[k]), 2, 1, GDT_Byte, 0, 0), CE_None);
    GDALClose(ds);
}
}  // namespace

TEST(CityReader, ReadsADemAsTerrainInTheUtmZoneOfItsCentre) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/lux_elev_srtm.tif");
    const CityModel m = readCityModel(path);
    EXPECT_EQ(m.crs, "EPSG:32632");  // Luxembourg, about 6 degrees east
    ASSERT_EQ(m.objects.size(), 1u);
    EXPECT_EQ(m.objects[0].role, CityRole::Terrain);
    const Box3 b = m.bounds();
    EXPECT_NEAR(b.lo.z, 141.0, 30.0);  // SRTM heights of Luxembourg, metres (cells averaged at the edges)
    EXPECT_NEAR(b.hi.z, 547.0, 30.0);
    EXPECT_GT(b.hi.x - b.lo.x, 40000.0);  // tens of kilometres, in metres
    CityRequest r;
    r.maxSamples = 17;  // fewer samples: GDAL averages
    EXPECT_LT(readCityModel(path, r).triangles.size(), 2u * 16u * 16u + 1u);
}

TEST(CityReader, DrapesATextureInAnotherCrsOnTheTerrain) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/lux_elev_srtm.tif");
    test::TempDir dir;
    const std::string tif = dir.file("two.tif");
    writeTwoColourTiff(tif, 5.5, 6.7, 49.3, 50.3);
    CityRequest r;
    r.texture = tif;
    r.maxSamples = 65;
    const CityModel m = readCityModel(path, r);
    ASSERT_FALSE(m.texture.empty());
    CityBuildOptions o;
    o.depth = 6;
    const Octree t = voxelizeCity(m, o);
    std::size_t red = 0, blue = 0, other = 0;
    const std::uint32_t kRed = 0xFF0000FFu, kBlue = 0xFFFF0000u;
    // Longitude 6.1 is the texture's middle: in UTM 32N (central meridian 9 E), east of x ~ 290 km.
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        const double x = t.voxelBox(c).centre().x;
        if (t.colours()[i] == kRed) red += x < 300000.0;
        else if (t.colours()[i] == kBlue) blue += x > 280000.0;
        else ++other;
    });
    EXPECT_GT(red, 100u);
    EXPECT_GT(blue, 100u);
    EXPECT_EQ(other, 0u);  // the texture covers all of Luxembourg
    r.texture = dir.file("absent.tif");
    EXPECT_THROW_WITH(readCityModel(path, r), InputError, "no such file");
    writeTwoColourTiff(tif, 100.0, 101.0, 10.0, 11.0);  // somewhere else
    r.texture = tif;
    EXPECT_THROW_WITH(readCityModel(path, r), InputError, "the texture does not cover the scene");
}

namespace {
void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
}

/// Three footprints in Amersfoort / RD New: a 10 m square (height 10, base 5), one without a
/// height, one self-intersecting (a bow tie).
const char* kFootprints = R"({"type": "FeatureCollection",
 "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::28992"}},
 "features": [
  {"type": "Feature", "properties": {"ID": "good", "h": 10.0, "ground": 5.0},
   "geometry": {"type": "Polygon", "coordinates": [[[155000, 463000], [155010, 463000], [155010, 463010], [155000, 463010], [155000, 463000]]]}},
  {"type": "Feature", "properties": {"ID": "noheight", "h": null, "ground": 5.0},
   "geometry": {"type": "Polygon", "coordinates": [[[155020, 463000], [155030, 463000], [155030, 463010], [155020, 463000]]]}},
  {"type": "Feature", "properties": {"ID": "bowtie", "h": 8.0, "ground": 5.0},
   "geometry": {"type": "MultiPolygon", "coordinates": [[[[155040, 463000], [155050, 463010], [155050, 463000], [155040, 463010], [155040, 463000]]]]}}
 ]})";
}  // namespace

TEST(CityReader, FootprintsBecomePrismsAndTheBrokenOnesAreSaidAndLeftOut) {
    test::TempDir dir;
    const std::string path = dir.file("f.geojson");
    writeText(path, kFootprints);
    CityRequest r;
    r.heightAttr = "h";
    r.baseAttr = "ground";
    const CityModel m = readCityModel(path, r);
    EXPECT_EQ(m.crs, "EPSG:28992");
    ASSERT_EQ(m.objects.size(), 1u);
    EXPECT_EQ(m.objects[0].id, "good");
    const Box3 b = m.bounds();
    EXPECT_EQ(b.lo, dvec3(155000, 463000, 5));
    EXPECT_EQ(b.hi, dvec3(155010, 463010, 15));
    ASSERT_EQ(m.notes.size(), 2u);
    EXPECT_NE(m.notes[0].find("1 footprint polygons self-intersecting or without area, left out (bowtie)"), std::string::npos) << m.notes[0];
    EXPECT_NE(m.notes[1].find("1 footprints without a height (h missing or not positive), left out (noheight)"), std::string::npos) << m.notes[1];
    // A .json GeoJSON goes to the same reader; no height attribute is an error naming the fields.
    const std::string json = dir.file("f.json");
    writeText(json, kFootprints);
    EXPECT_THROW_WITH(readCityModel(json), InputError, "no height attribute found; give `height_attr` (its attributes: ID, h, ground)");
    r.baseAttr = "floor";
    EXPECT_THROW_WITH(readCityModel(json, r), InputError, "no attribute 'floor' (`base_attr`)");
}

TEST(CityReader, AFootprintFileInTheWrongCrsIsAClearError) {
    test::TempDir dir;
    const std::string path = dir.file("wrong.geojson");
    std::string text = kFootprints;
    text.replace(text.find("EPSG::28992"), 11, "EPSG::4326");  // metres taken as degrees
    writeText(path, text);
    CityRequest r;
    r.heightAttr = "h";
    EXPECT_THROW_WITH(readCityModel(path, r), InputError, "no coordinate could be transformed from EPSG:4326 to EPSG:");
}

TEST(CityReader, FootprintsStandOnTheDemWithoutABaseAttribute) {
    OCTRACE_SHARED_FILE_OR_SKIP(dem, "city/lux_elev_srtm.tif");
    test::TempDir dir;
    const std::string path = dir.file("lux.geojson");
    // A 0.001 degree square in Luxembourg City, 20 m high.
    writeText(path, R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"height": 20},
        "geometry": {"type": "Polygon", "coordinates": [[[6.130, 49.610], [6.131, 49.610], [6.131, 49.611], [6.130, 49.611], [6.130, 49.610]]]}}]})");
    CityRequest r;
    r.dem = dem;
    const CityModel m = readCityModel(path, r);
    EXPECT_EQ(m.crs, "EPSG:32632");
    ASSERT_EQ(m.objects.size(), 2u);  // the building and the DEM's terrain
    Box3 building;
    building.lo = dvec3(1e300);
    building.hi = -building.lo;
    for (const auto& t : m.triangles)
        if (m.objects[t.object].type == "Building")
            for (auto i : t.v) {
                building.lo = glm::min(building.lo, m.vertices[i]);
                building.hi = glm::max(building.hi, m.vertices[i]);
            }
    EXPECT_GT(building.lo.z, 200.0);  // Luxembourg City's plateau, about 300 m
    EXPECT_LT(building.lo.z, 420.0);
    EXPECT_NEAR(building.hi.z - building.lo.z, 20.0, 1e-9);
}

TEST(CityReader, ReadsTheLyonFootprintsWithTheirGroundAndHeight) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/buildings_lyon1.geojson");
    CityRequest r;
    r.heightAttr = "HAUTEUR";
    r.baseAttr = "Z_MIN_SOL";
    const CityModel m = readCityModel(path, r);
    EXPECT_EQ(m.crs, "EPSG:3946");
    EXPECT_EQ(m.objects.size(), 2571u);  // 2,576 less 5 without Z_MIN_SOL, said in a note
    ASSERT_EQ(m.notes.size(), 1u);
    EXPECT_NE(m.notes[0].find("5 footprints without a base (Z_MIN_SOL missing)"), std::string::npos);
    // BATIMENT0000000240876972: ground 200.6 m, height 9.2 m.
    const auto it = std::find_if(m.objects.begin(), m.objects.end(), [](const CityObject& o) { return o.id == "BATIMENT0000000240876972"; });
    ASSERT_NE(it, m.objects.end());
    const std::uint32_t index = std::uint32_t(it - m.objects.begin());
    double lo = 1e300, hi = -1e300;
    for (const auto& t : m.triangles)
        if (t.object == index)
            for (auto i : t.v) {
                lo = std::min(lo, m.vertices[i].z);
                hi = std::max(hi, m.vertices[i].z);
            }
    EXPECT_NEAR(lo, 200.6, 1e-9);
    EXPECT_NEAR(hi, 209.8, 1e-9);
}

namespace {
/// A CityGML 2.0 document around `members` (cityObjectMember elements).
std::string cityGml(const std::string& members, const std::string& srs = "urn:ogc:def:crs,crs:EPSG::25833,crs:EPSG::5783") {
    return "<?xml version=\"1.0\"?>\n<core:CityModel xmlns:core=\"http://www.opengis.net/citygml/2.0\" "
           "xmlns:bldg=\"http://www.opengis.net/citygml/building/2.0\" xmlns:gml=\"http://www.opengis.net/gml\" "
           "xmlns:xlink=\"http://www.w3.org/1999/xlink\"><gml:boundedBy><gml:Envelope srsName=\"" + srs +
           "\"/></gml:boundedBy>" + members + "</core:CityModel>";
}
std::string polygon(const std::string& id, const std::string& posList, const std::string& hole = "") {
    return "<gml:Polygon" + (id.empty() ? std::string() : " gml:id=\"" + id + "\"") +
           "><gml:exterior><gml:LinearRing><gml:posList>" + posList + "</gml:posList></gml:LinearRing></gml:exterior>" +
           (hole.empty() ? "" : "<gml:interior><gml:LinearRing><gml:posList>" + hole + "</gml:posList></gml:LinearRing></gml:interior>") +
           "</gml:Polygon>";
}
/// A house: a 10 x 10 floor with a 2 x 2 hole at LoD2, a gable roof (two slopes, one given by
/// an xlink reference), and an LoD1 block.
std::string houseGml() {
    return cityGml(
        "<core:cityObjectMember><bldg:Building gml:id=\"house\">"
        "<bldg:lod1Solid><gml:Solid><gml:exterior><gml:CompositeSurface><gml:surfaceMember>" +
        polygon("", "0 0 0 10 0 0 10 10 0 0 10 0 0 0 0") +
        "</gml:surfaceMember></gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod1Solid>"
        "<bldg:boundedBy><bldg:GroundSurface><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>" +
        polygon("", "0 0 0 0 10 0 10 10 0 10 0 0 0 0 0", "4 4 0 6 4 0 6 6 0 4 6 0 4 4 0") +
        "</gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:GroundSurface></bldg:boundedBy>"
        "<bldg:boundedBy><bldg:RoofSurface><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>" +
        polygon("", "0 0 5 10 0 5 10 5 8 0 5 8 0 0 5") +
        "</gml:surfaceMember><gml:surfaceMember xlink:href=\"#north\"/>"
        "</gml:MultiSurface></bldg:lod2MultiSurface></bldg:RoofSurface></bldg:boundedBy>"
        "</bldg:Building></core:cityObjectMember>"
        "<core:cityObjectMember><bldg:Building gml:id=\"shed\"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>" +
        polygon("north", "0 5 8 10 5 8 10 10 5 0 10 5 0 5 8") + "</gml:surfaceMember><gml:surfaceMember>" +
        polygon("", "20 0 0 21 0 0 21 1") +  // an odd number of coordinates: broken
        "</gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:Building></core:cityObjectMember>");
}
}  // namespace

TEST(CityGml, ReadsLod2SurfacesWithRoofsHolesAndReferencesAndTheCompoundCrs) {
    const CityModel m = io::detail::parseCityGml(houseGml(), "house.gml", "");
    EXPECT_EQ(m.crs, "EPSG:25833");
    EXPECT_EQ(m.format, "CityGML");
    // house: its body (the floor) and its roof; shed: the referenced slope (its own polygon).
    ASSERT_EQ(m.objects.size(), 3u);
    EXPECT_EQ(m.objects[0].type, "Building");
    EXPECT_EQ(m.objects[1].type, "RoofSurface");
    EXPECT_EQ(m.objects[1].id, "house");
    double floor = 0.0, roof = 0.0;
    for (const auto& t : m.triangles) {
        const dvec3 a = m.vertices[t.v[0]], b = m.vertices[t.v[1]], c = m.vertices[t.v[2]];
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        (t.object == 0 ? floor : t.object == 1 ? roof : floor) += t.object == 2 ? 0.0 : area;
    }
    EXPECT_NEAR(floor, 100.0 - 4.0, 1e-9);                   // the hole left open
    EXPECT_NEAR(roof, 2.0 * 10.0 * std::hypot(5.0, 3.0), 1e-9);  // both slopes, one through xlink:href
    bool broken = false;
    for (const auto& n : m.notes) broken = broken || n.find("1 polygons with broken coordinates, left out (shed)") != std::string::npos;
    EXPECT_TRUE(broken);
    // --lod-select 1: the LoD1 block only; 3: none.
    const CityModel l1 = io::detail::parseCityGml(houseGml(), "house.gml", "1");
    ASSERT_EQ(l1.objects.size(), 1u);
    EXPECT_EQ(l1.triangles.size(), 2u);
    try {
        io::detail::parseCityGml(houseGml(), "house.gml", "3");
        FAIL() << "no LoD 3";
    } catch (const EmptyResultError& e) {
        EXPECT_NE(std::string(e.what()).find("no object has a geometry of LoD 3"), std::string::npos) << e.what();
    }
    EXPECT_EQ(io::detail::parseCityGml(cityGml("<core:cityObjectMember><bldg:Building>" + std::string("<bldg:lod2MultiSurface>") +
                                               polygon("", "0 0 0 1 0 0 0 1 0 0 0 0") + "</bldg:lod2MultiSurface></bldg:Building></core:cityObjectMember>",
                                           "urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH"),
                                   "adv.gml", "")
                  .crs,
              "EPSG:25832");
}

TEST(CityGml, RefusesTextThatIsNotCityGml) {
    EXPECT_THROW(io::detail::parseCityGml("<a><b></a>", "x.gml", ""), FileError);
    EXPECT_THROW(io::detail::parseCityGml("<FeatureCollection/>", "x.gml", ""), FormatNotSupported);
    EXPECT_THROW(io::detail::parseCityGml(cityGml(""), "x.gml", ""), EmptyResultError);
    std::string deep;
    for (int i = 0; i < 300; ++i) deep += "<g>";
    for (int i = 0; i < 300; ++i) deep += "</g>";
    try {
        io::detail::parseCityGml(cityGml(deep), "deep.gml", "");
        FAIL() << "300 levels accepted";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("deep.gml: elements nested more than 256 deep"), std::string::npos) << e.what();
    }
}

TEST(CityGml, ReadsBerlinsLod2BuildingsWithTheirRoofs) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "city/berlin_open_data_sample_data.citygml");
    const CityModel m = readCityModel(path);
    EXPECT_EQ(m.crs, "EPSG:25833");
    std::size_t buildings = 0, roofs = 0;
    for (const auto& o : m.objects) {
        buildings += o.type == "Building";
        roofs += o.type == "RoofSurface";
    }
    EXPECT_EQ(buildings, 61u);
    EXPECT_EQ(roofs, 61u);
    // LoD2 roofs: sloped roof triangles (neither flat nor a wall), not only LoD1 blocks.
    std::size_t sloped = 0;
    for (const auto& t : m.triangles) {
        if (m.objects[t.object].type != "RoofSurface") continue;
        const dvec3 a = m.vertices[t.v[0]], b = m.vertices[t.v[1]], c = m.vertices[t.v[2]];
        const double nz = std::abs(glm::normalize(glm::cross(b - a, c - a)).z);
        sloped += nz > 0.2 && nz < 0.95;
    }
    EXPECT_GT(sloped, 50u);
    const Box3 b = m.bounds();
    EXPECT_NEAR(b.lo.z, 27.52, 0.01);  // the envelope's heights
    EXPECT_NEAR(b.hi.z, 64.22, 0.01);
    CityRequest r;
    r.lod = "1";
    EXPECT_THROW(readCityModel(path, r), EmptyResultError);  // LoD2 only
    const std::string info = describeCityInput(path);
    EXPECT_NE(info.find("crs: EPSG:25833"), std::string::npos) << info;
    EXPECT_NE(info.find("format: CityGML"), std::string::npos) << info;
}

TEST(CityScene, CombinesSourcesWithTheirDepthColourAndRole) {
    octrace::test::TempDir dir;
    const std::string scene = dir.file("two.scene.json");
    {
        std::ofstream f(scene);
        f << R"({"crs": "EPSG:28992", "sources": [
              {"path": ")" << kCube << R"(", "colour": [1, 0, 0]},
              {"path": ")" << kCube << R"(", "lod": "1", "role": "terrain", "depth": 3, "colour": [0, 0, 1]}]})";
    }
    const CityModel m = readCityModel(scene);
    EXPECT_EQ(m.crs, "EPSG:28992");
    EXPECT_EQ(m.format, "city scene (2 sources)");
    const CityModel cube = readCityModel(kCube);
    ASSERT_GT(m.objects.size(), cube.objects.size());
    for (std::size_t i = 0; i < m.objects.size(); ++i) {
        const bool second = i >= cube.objects.size();
        EXPECT_EQ(m.objects[i].colour, packColour(second ? vec3(0, 0, 1) : vec3(1, 0, 0)));
        EXPECT_EQ(m.objects[i].depth, second ? 3 : 0);
        if (second) {
            EXPECT_EQ(m.objects[i].role, CityRole::Terrain);
        }
    }
    // The second source stops at level 3: coarse leaves, blue; the first goes to the depth.
    CityBuildOptions o;
    o.depth = 6;
    const Octree t = voxelizeCity(m, o);
    t.validate();
    ASSERT_TRUE(t.hasCoarseLeaves());
    t.forEachLeaf([&](const ivec3&, int shift, std::uint32_t v) {
        if (shift > 0) {
            EXPECT_EQ(t.colours()[v], packColour(vec3(0, 0, 1)));
        }
    });
    o.depth = 2;
    EXPECT_THROW(voxelizeCity(m, o), UsageError);  // a source deeper than the octree
}

TEST(CityScene, RefusesBadKeysAndValuesNamingThem) {
    auto refused = [](const std::string& text, const std::string& what) {
        try {
            io::detail::parseCityScene(text, "s.scene.json");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    refused("{", "s.scene.json: not valid JSON");
    refused(R"({"sources": [{"path": "a.json", "depth": 1e999}]})", "s.scene.json: not valid JSON");
    refused("{}", "no \"sources\" array");
    refused(R"({"sources": []})", "\"sources\" must be a non-empty array");
    refused(R"({"sources": [{"depth": 3}]})", "sources[0] has no \"path\"");
    refused(R"({"sources": [{"path": "a.json", "depth": 15}]})", "sources[0].\"depth\" must be an integer in 1..14");
    refused(R"({"sources": [{"path": "a.json", "colour": [1, 2, 0]}]})", "sources[0].\"colour\" must be [r, g, b] in [0, 1]");
    refused(R"({"sources": [{"path": "a.json", "role": "water"}]})", "\"role\" must be \"terrain\" or \"solid\"");
    refused(R"({"sources": [{"path": "a.json", "heigth_attr": "h"}]})", "\"heigth_attr\" is not a source key");
    refused(R"({"source": []})", "\"source\" is not a scene key");
    const auto s = io::detail::parseCityScene(R"({"texture": "t.tif", "sources": [{"path": "a.geojson", "height_attr": "H", "base_attr": "B"}]})", "s");
    EXPECT_EQ(s.texture, "t.tif");
    ASSERT_EQ(s.sources.size(), 1u);
    EXPECT_EQ(s.sources[0].heightAttr, "H");
    EXPECT_EQ(s.sources[0].baseAttr, "B");
}

// The CF interpretation of in-memory arrays (octrace/io/CfDataset.h) against the file path
// (NetcdfReader): a CfDataset built from a file's own arrays and attributes, as the Python
// package builds one from an xarray DataArray, must give the file's field bit for bit; and
// inconsistent arrays are refused with InputError naming the variable.
#include "CfDatasetFromGdal.h"
#include "CfFileWriter.h"
#include "IoTestSupport.h"
#include "SameField.h"

#include "octrace/io/CfDataset.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace octrace;
using test::CfFileWriter;
using test::expectSameField;

namespace {

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

// The file's and the memory's field for `req`, compared; also their warnings (the path replaced
// by the description).
void expectSameRead(const std::string& path, const io::CfDataset& data, const io::FieldRequest& req) {
    std::vector<std::string> fileWarnings, memoryWarnings;
    ScalarField file, memory;
    {
        test::LogCapture log;
        file = io::NetcdfReader::read(path, req);
        for (const auto& w : log.warnings) fileWarnings.push_back(replaceAll(w, path, data.description));
    }
    {
        test::LogCapture log;
        memory = io::readCfDataset(data, req);
        memoryWarnings = log.warnings;
    }
    EXPECT_EQ(file.source, path);
    EXPECT_EQ(memory.source, data.description);
    expectSameField(file, memory);
    EXPECT_EQ(memoryWarnings, fileWarnings);
}

// Both refuse `req` with the same exception type and message (the path replaced).
template <class E>
void expectSameRefusal(const std::string& path, const io::CfDataset& data, const io::FieldRequest& req) {
    std::string fromFile, fromMemory;
    try {
        (void)io::NetcdfReader::read(path, req);
    } catch (const E& e) {
        fromFile = replaceAll(e.what(), path, data.description);
    }
    try {
        (void)io::readCfDataset(data, req);
    } catch (const E& e) {
        fromMemory = e.what();
    }
    EXPECT_FALSE(fromFile.empty());
    EXPECT_EQ(fromMemory, fromFile);
}

io::FieldRequest variable(const std::string& name) {
    io::FieldRequest r;
    r.variable = name;
    return r;
}

}  // namespace

TEST(CfDatasetLevitus, ArraysInMemoryGiveTheFilesFieldBitForBit) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "ocean/levitus_climatology.cdf");
    auto mem = test::cfDatasetFromGdal(path, "xarray DataArray TEMP");
    const io::CfDataset& data = mem->data;

    io::FieldRequest deep = test::regionRequest("TEMP", 0, 90, -45, 45);
    deep.hasDepthRange = true;
    deep.depthRange[0] = 50;
    deep.depthRange[1] = 1500;
    deep.verticalScale = 25;
    const std::pair<const char*, io::FieldRequest> cases[] = {
        {"TEMP by name, whole grid", variable("TEMP")},
        {"region across 180 degrees", test::regionRequest("TEMP", 120, 200, 10, 60)},
        {"region across the dateline written 170,-170", test::regionRequest("SALT", 170, -170, -30, 30)},
        {"depth range and vertical scale", deep},
        {"sound speed derived from TEMP and SALT", test::regionRequest("sound_speed", 140, 240, 0, 60)},
    };
    for (const auto& [what, req] : cases) {
        SCOPED_TRACE(what);
        expectSameRead(path, data, req);
    }
    expectSameRefusal<InputError>(path, data, variable("DENSITY"));  // unknown: refused alike
    // Without `var` both refuse the two volumes alike; with the dataset cut to TEMP alone (as
    // a DataArray brings it), the default variable is TEMP.
    expectSameRefusal<InputError>(path, data, {});
    io::CfDataset temp;
    temp.description = data.description;
    for (const auto& v : data.variables)
        if (v.name != "SALT") temp.variables.push_back(v);
    expectSameField(io::NetcdfReader::read(path, variable("TEMP")), io::readCfDataset(temp, {}));
    EXPECT_EQ(io::cfVolumeVariables(data), io::NetcdfReader::volumeVariables(path));
    EXPECT_EQ(io::cfVolumeVariables(temp), std::vector<std::string>{"TEMP"});

    // The memory budget is refused up front with the file path's words.
    io::FieldRequest small = variable("TEMP");
    small.memoryBudget = 1'000'000;
    expectSameRefusal<LimitError>(path, data, small);

    // `octrace info`'s text: the same after the format line.
    auto body = [](const std::string& text) { return text.substr(text.find("\ndimensions:")); };
    const io::FieldRequest described = test::regionRequest("TEMP", 120, 200, 10, 60);
    const std::string fromFile = replaceAll(io::NetcdfReader::describe(path, described), path, data.description);
    const std::string fromMemory = io::describeCfDataset(data, described);
    EXPECT_EQ(body(fromMemory), body(fromFile));
    EXPECT_EQ(fromMemory.rfind("xarray DataArray TEMP\nformat: in-memory arrays", 0), 0u) << fromMemory;
}

namespace {

// time(3) x height(4) x lat(3) x lon(4): heights positive up, uneven, negative below the
// surface; time in days since 2000-01-01 in the 360_day calendar; `temp` Float32 with a
// _FillValue and NaNs; `packed` int16 with scale_factor, add_offset, _FillValue, missing_value
// and valid_range.
void syntheticFile(const std::string& path) {
    CfFileWriter w(path);
    w.coordinate("time", {0, 30, 60}, {{"units", "days since 2000-01-01"}, {"calendar", "360_day"}, {"standard_name", "time"}});
    w.coordinate("height", {-800, -150, -20, 0}, {{"units", "m"}, {"positive", "up"}});
    w.coordinate("lat", {-10, 0, 10}, {{"units", "degrees_north"}});
    w.coordinate("lon", {170, 180, 190, 200}, {{"units", "degrees_east"}});
    std::vector<double> temp, packed;
    for (int t = 0; t < 3; ++t)
        for (int k = 0; k < 4; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 4; ++i) {
                    temp.push_back(1000 * t + 100 * k + 10 * j + i + 0.25);
                    packed.push_back(-2000 + 300 * t + 50 * k + 7 * j + i);
                }
    temp[1] = -999;                                          // _FillValue
    temp[13] = std::numeric_limits<double>::quiet_NaN();     // NaN
    temp[48 + 5] = std::numeric_limits<double>::quiet_NaN(); // NaN at time step 1
    packed[2] = -32767;                                      // _FillValue
    packed[48 + 3] = -32000;                                 // missing_value
    packed[48 + 4] = 3000;                                   // beyond valid_range
    auto t = w.variable("temp", {"time", "height", "lat", "lon"}, GDT_Float32, temp,
                        {{"units", "degC"}, {"long_name", "sea temperature"}, {"standard_name", "sea_water_temperature"}});
    t->SetNoDataValue(-999.0);
    auto p = w.variable("packed", {"time", "height", "lat", "lon"}, GDT_Int16, packed, {{"units", "PSU"}});
    p->SetNoDataValue(-32767.0);
    p->SetScale(0.01);
    p->SetOffset(35.0);
    CfFileWriter::numbers(*p, "missing_value", GDT_Int16, {-32000});
    CfFileWriter::numbers(*p, "valid_range", GDT_Int16, {-2500, 2500});
}

}  // namespace

TEST(CfDatasetSynthetic, HeightsUpUnevenLevelsMasksPackingAnd360DayTimeMatchTheFile) {
    test::TempDir dir;
    const std::string path = dir.file("synthetic.nc");
    syntheticFile(path);
    auto mem = test::cfDatasetFromGdal(path, "xarray DataArray temp");
    const io::CfDataset& data = mem->data;

    for (const char* var : {"temp", "packed"})
        for (const char* time : {"", "1", "2000-02-01", "2000-02-30", "2001-06-01"}) {
            SCOPED_TRACE(std::string(var) + " at time '" + time + "'");
            io::FieldRequest r;
            r.variable = var;
            r.time = time;
            expectSameRead(path, data, r);
            r.hasDepthRange = true;
            r.depthRange[0] = 10;
            r.depthRange[1] = 200;
            r.verticalScale = 3;
            expectSameRead(path, data, r);
        }
    // A date outside the 360_day calendar, and a step beyond the axis, are refused alike.
    io::FieldRequest r;
    r.variable = "temp";
    r.time = "2000-02-31";
    expectSameRefusal<InputError>(path, data, r);
    r.time = "7";
    expectSameRefusal<InputError>(path, data, r);

    // What the in-memory path found, said directly: 30 days is 2000-02-01 in 360_day, the NaN
    // and the _FillValue are masked, the int16 samples unpacked.
    r.time = "2000-02-01";
    ScalarField f = io::readCfDataset(data, r);
    ASSERT_EQ(f.dims, ivec3(4, 3, 4));
    EXPECT_NE(std::find(f.notes.begin(), f.notes.end(), "`time` 2000-02-01: nearest step 1 of 3 (2000-02-01, calendar 360_day)"),
              f.notes.end());
    EXPECT_FALSE(f.isValid(f.index(1, 1, 0)));  // height -800 m (the deepest, lowest z), lat 0, lon 180: NaN
    EXPECT_EQ(f.values[f.index(0, 0, 3)], float(1000 + 3 * 100 + 0.25));  // height 0, the surface, on top
    EXPECT_EQ(f.validCount(), 47u);
    EXPECT_EQ(f.coords[2].size(), 4u);  // uneven heights stay rectilinear
    io::FieldRequest p;
    p.variable = "packed";
    test::LogCapture log;  // the first time step, with a warning
    ScalarField g = io::readCfDataset(data, p);
    EXPECT_EQ(log.warnings.size(), 1u);
    EXPECT_FALSE(g.isValid(g.index(2, 0, 0)));  // _FillValue at the deepest level
    EXPECT_EQ(g.values[g.index(1, 0, 0)], float((-2000 + 1) * 0.01 + 35.0));
}

namespace {

// lon(4) x lat(3) x depth(3) with a temp(depth, lat, lon) of owned doubles.
io::CfDataset smallDataset() {
    io::CfDataset d;
    d.description = "test arrays";
    auto coord = [&](const std::string& name, std::vector<double> values, const std::string& units) {
        io::CfVariable v;
        v.name = name;
        v.dims = {name};
        v.shape = {values.size()};
        v.values = std::move(values);
        v.attributes["units"] = units;
        d.variables.push_back(std::move(v));
    };
    coord("depth", {0, 100, 500}, "m");
    coord("lat", {-10, 0, 10}, "degrees_north");
    coord("lon", {10, 20, 30, 40}, "degrees_east");
    d.variables[0].attributes["positive"] = "down";
    io::CfVariable t;
    t.name = "temp";
    t.dims = {"depth", "lat", "lon"};
    t.shape = {3, 3, 4};
    t.values = std::vector<double>(36, 4.0);
    d.variables.push_back(std::move(t));
    return d;
}

io::CfVariable& variableOf(io::CfDataset& d, const std::string& name) {
    for (auto& v : d.variables)
        if (v.name == name) return v;
    throw std::runtime_error("no " + name);
}

}  // namespace

TEST(CfDatasetInvalid, ConsistentSmallDatasetIsRead) {
    ScalarField f = io::readCfDataset(smallDataset(), {});
    EXPECT_EQ(f.dims, ivec3(4, 3, 3));
    EXPECT_EQ(f.source, "test arrays");
    EXPECT_TRUE(f.geographic.valid);
}

TEST(CfDatasetInvalid, ShapeDisagreeingWithDimensionNamesIsRefusedNamingTheVariable) {
    io::CfDataset d = smallDataset();
    variableOf(d, "temp").shape = {3, 3};
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError,
                      "test arrays: variable 'temp' has 3 dimension name(s) for a shape of 2 (3 x 3)");
}

TEST(CfDatasetInvalid, TooFewOrTooManyValuesAreRefusedNamingTheVariable) {
    io::CfDataset d = smallDataset();
    variableOf(d, "temp").values = std::vector<double>(35, 4.0);
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError, "variable 'temp': shape 3 x 3 x 4 needs 36 values, 35 given");
    // A shape far larger than the values handed over (the product saturates) is refused too.
    const std::vector<float> few(4, 1.0f);
    io::CfDataset huge = smallDataset();
    variableOf(huge, "temp").shape = {std::size_t(1) << 40, std::size_t(1) << 40, 4};
    variableOf(huge, "temp").values = std::span<const float>(few);
    EXPECT_THROW_WITH(io::cfVolumeVariables(huge), InputError, "variable 'temp'");
}

TEST(CfDatasetInvalid, CoordinateOfTheWrongLengthIsRefusedNamingIt) {
    io::CfDataset d = smallDataset();
    io::CfVariable& lon = variableOf(d, "lon");
    lon.shape = {5};
    lon.values = std::vector<double>{10, 20, 30, 40, 50};
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError,
                      "test arrays: variable 'temp': dimension 'lon' has 4 points, but 5 in variable 'lon'");
}

TEST(CfDatasetInvalid, NonFiniteCoordinatesAreRefusedNamingTheVariable) {
    io::CfDataset d = smallDataset();
    std::get<std::vector<double>>(variableOf(d, "lat").values)[1] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError,
                      "test arrays: coordinate variable 'lat' of dimension 'lat' holds a non-finite value (nan at index 1)");
    EXPECT_THROW_WITH(io::describeCfDataset(d), InputError, "coordinate variable 'lat'");
}

TEST(CfDatasetInvalid, TwoDimensionalDataIsRefusedNamingTheVariable) {
    io::CfDataset d = smallDataset();
    io::CfVariable& t = variableOf(d, "temp");
    t.dims = {"lat", "lon"};
    t.shape = {3, 4};
    t.values = std::vector<double>(12, 4.0);
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError, "test arrays: no 3-D variable (variables: temp(lat, lon))");
    io::FieldRequest r;
    r.variable = "temp";
    EXPECT_THROW_WITH(io::readCfDataset(d, r), InputError,
                      "test arrays: variable temp(lat, lon) is a 2-D field (a map over lat and lon): a surface needs a 3-D "
                      "field; draw a 2-D field with slice");
    r.acceptPlanar = true;  // as slices read it: a map
    const ScalarField map = io::readCfDataset(d, r);
    EXPECT_TRUE(map.planar);
    EXPECT_EQ(map.dims, ivec3(4, 3, 1));
}

// Maps (FieldRequest::acceptPlanar): the real ETOPO20 relief, and the Levitus-derived 2-D and
// OISST-like files of tests/data/netcdf/make_maps.py, alike from memory and from the file.
TEST(CfDatasetMaps, ArraysInMemoryGiveTheFilesMapBitForBit) {
    std::vector<std::string> paths = {test::testData("netcdf/levitus_sst_2d.nc"), test::testData("netcdf/oisst_like_zlev.nc")};
    const std::string etopo = test::sharedData("ocean/etopo20.cdf");
    if (!etopo.empty()) paths.push_back(etopo);
    for (const auto& path : paths) {
        SCOPED_TRACE(path);
        auto mem = test::cfDatasetFromGdal(path, "xarray DataArray");
        io::FieldRequest map;
        map.acceptPlanar = true;
        expectSameRead(path, mem->data, map);
        io::FieldRequest region = test::regionRequest("", -60, 30, -20, 50);  // across the seam of both files
        region.acceptPlanar = true;
        expectSameRead(path, mem->data, region);
        expectSameRefusal<InputError>(path, mem->data, {});  // a surface: refused alike
    }
}

TEST(CfDatasetInvalid, UnnamedRepeatedOrValuelessVariablesAreRefusedOrSkipped) {
    io::CfDataset d = smallDataset();
    d.variables.push_back(variableOf(d, "lat"));
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError, "test arrays: two variables are named 'lat'");
    d = smallDataset();
    d.variables.emplace_back();
    EXPECT_THROW_WITH(io::readCfDataset(d, {}), InputError, "test arrays: a variable has no name");
    // A variable without numeric values (e.g. text labels) is listed but not read.
    d = smallDataset();
    io::CfVariable label;
    label.name = "label";
    label.dims = {"lon"};
    label.shape = {4};
    d.variables.push_back(label);
    EXPECT_EQ(io::readCfDataset(d, {}).name, "temp");
    io::FieldRequest r;
    r.variable = "label";
    EXPECT_THROW_WITH(io::readCfDataset(d, r), InputError, "test arrays: variable 'label' is not numeric");
}

// Zarr stores through GDAL's Zarr driver and the NetCDF path's CF interpretation: the stores
// tests/data/zarr/make_zarr_stores.py makes from the Levitus atlas (GDAL's writer, xarray's
// with Blosc, consolidated or not, all-land chunks left out, the pre-final v3 draft, a final v3
// store converted as the refusal says) give the NetCDF file's fields bit for bit; the layout
// checks of io/src/zarr/ZarrStore.cpp on metadata bytes; folders told apart by content.
#include "../ZarrStores.h"
#include "IoTestSupport.h"
#include "SameField.h"

#include "octrace/io/FieldReader.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/util/Error.h"
#include "zarr/ZarrStore.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <filesystem>
#include <fstream>

using namespace octrace;
namespace detail = octrace::io::detail;
namespace fs = std::filesystem;

namespace {

const char* kStores[] = {"levitus_gdal.zarr",           "levitus_gdal_v3draft.zarr",     "levitus_xr_consolidated.zarr",
                         "levitus_xr_unconsolidated.zarr", "levitus_missing_chunks.zarr", "levitus_v3_v2.zarr"};

io::FieldRequest variable(const std::string& name) {
    io::FieldRequest r;
    r.variable = name;
    return r;
}

detail::ZarrMetadata v2Group(const std::string& zgroup) {
    detail::ZarrMetadata m;
    m.zgroup = zgroup;
    return m;
}

}  // namespace

TEST(Zarr, EveryStoreGivesTheNetcdfFieldBitForBit) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    const std::vector<io::FieldRequest> requests = {variable("TEMP"), variable("SALT"),
                                                    test::regionRequest("TEMP", 120, 180, 10, 60),
                                                    test::regionRequest("SALT", 170, -170, -30, 30)};
    for (const auto& req : requests) {
        const ScalarField fromFile = io::readField(levitus, req);
        for (const char* store : kStores) {
            SCOPED_TRACE(std::string(store) + " " + req.variable);
            test::expectSameField(fromFile, io::readField(dir + "/" + store, req));
        }
    }
    // Sound speed derived from TEMP and SALT alike.
    io::FieldRequest sound = test::regionRequest("sound_speed", 120, 180, 10, 60);
    test::expectSameField(io::readField(levitus, sound), io::readField(dir + "/levitus_xr_consolidated.zarr", sound));
}

// Ocean stores leave out all-land chunks: the Zarr spec reads them as the fill value, which
// xarray wrote from _FillValue, so they are masked like the NetCDF file's land.
TEST(Zarr, MissingChunksReadAsTheFillValue) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    const std::string store = dir + "/levitus_missing_chunks.zarr";
    const int missing = std::stoi(test::readText(store + "/MISSING_CHUNKS"));
    EXPECT_EQ(missing, 16);  // 8 of TEMP's 288 chunks of 5 x 30 x 30, as many of SALT's (zarr-python wrote none of them)
    // Chunk 0.4.1 of TEMP (levels 0-4, 30.5-59.5 N, 50.5-79.5 E: Central Asia) is absent, and
    // its samples are masked.
    ASSERT_FALSE(fs::exists(store + "/TEMP/0.4.1"));
    ASSERT_TRUE(fs::exists(store + "/TEMP/0.4.0"));
    const ScalarField f = io::readField(store, variable("TEMP"));
    ASSERT_EQ(f.dims, ivec3(360, 180, 20));
    ASSERT_FALSE(f.valid.empty());
    // x = longitude from 20.5 E, y = latitude from 89.5 S, z upwards (level L at z = 19 - L).
    std::size_t masked = 0;
    for (int level = 0; level < 5; ++level)
        for (int j = 120; j < 150; ++j)
            for (int i = 30; i < 60; ++i) masked += f.isValid(f.index(i, j, f.dims.z - 1 - level)) ? 0 : 1;
    EXPECT_EQ(masked, 5u * 30u * 30u);
    test::expectSameField(io::readField(levitus, variable("TEMP")), f);
}

TEST(Zarr, InfoDescribesTheStoreAsTheNetcdfFile) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    const std::string store = dir + "/levitus_xr_consolidated.zarr";
    const std::string zarr = io::describeInput(store, variable("TEMP")), netcdf = io::describeInput(levitus, variable("TEMP"));
    EXPECT_NE(zarr.find("format: Zarr v2 store (consolidated metadata, .zmetadata: 6 arrays), read through GDAL's Zarr driver"),
              std::string::npos)
        << zarr;
    EXPECT_NE(zarr.find("TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR) Float32 [20 x 180 x 360], units 'DEG C'"), std::string::npos)
        << zarr;
    EXPECT_NE(zarr.find("ZAXLEVITR = 20: vertical (positive down), units 'METERS', 0 .. 5000, uneven"), std::string::npos)
        << zarr;
    // Below the format line, the NetCDF file's lines but for the fill-value attributes GDAL
    // shows (a Zarr array's fill_value is no attribute), in another order: GDAL lists a Zarr
    // store's arrays by name, a NetCDF file's in the file's order.
    const auto lines = [](const std::string& s) {
        std::vector<std::string> out;
        std::istringstream in(s.substr(s.find("dimensions:")));
        for (std::string line; std::getline(in, line);) {
            for (const char* attr : {", _FillValue -1e+10", ", missing_value -1e+10"})
                for (std::size_t at = line.find(attr); at != std::string::npos; at = line.find(attr))
                    line.erase(at, std::strlen(attr));
            out.push_back(line);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    EXPECT_EQ(lines(zarr), lines(netcdf));
    EXPECT_NE(io::describeInput(dir + "/levitus_xr_unconsolidated.zarr").find("Zarr v2 store (metadata not consolidated)"),
              std::string::npos);
    EXPECT_NE(io::describeInput(dir + "/levitus_gdal_v3draft.zarr").find("pre-final draft layout"), std::string::npos);
}

TEST(Zarr, FolderChoicesAndTimeAxisComeFromTheStore) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    const std::string store = dir + "/levitus_gdal.zarr";
    EXPECT_EQ(io::listInputChoices(store).variables, (std::vector<std::string>{"SALT", "TEMP"}));
    EXPECT_EQ(io::NetcdfReader::volumeVariables(store), io::listInputChoices(store).variables);
    EXPECT_EQ(io::readTimeAxis(store, variable("TEMP")).size, 0u);  // the atlas has no time axis
    // A trailing slash names the same store.
    test::expectSameField(io::readField(store, variable("TEMP")), io::readField(store + "/", variable("TEMP")));
}

TEST(Zarr, FinalV3LayoutIsRefusedWithHowToConvert) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    const std::string store = dir + "/levitus_v3.zarr";
    for (const auto& call : {+[](const std::string& p) { (void)io::readField(p, {}); },
                             +[](const std::string& p) { (void)io::describeInput(p, {}); },
                             +[](const std::string& p) { (void)io::listInputChoices(p); }}) {
        EXPECT_THROW_WITH(call(store), FormatNotSupported,
                          store + ": a Zarr v3 store in the final layout (zarr.json with \"zarr_format\": 3");
        EXPECT_THROW_WITH(call(store), FormatNotSupported,
                          "xr.open_zarr(\"" + store + "\").drop_encoding().to_zarr(\"" + dir +
                              "/levitus_v3_v2.zarr\", zarr_format=2)");
    }
}

TEST(Zarr, CorruptChunkNamesTheStoreAndTheVariable) {
    const std::string store = test::testData("invalid/invalid_corrupt_chunk.zarr");
    EXPECT_THROW_WITH(io::readField(store, variable("TEMP")), FileError,
                      store + ": cannot read variable 'TEMP' of the Zarr store: Decompression of tile");
    // The other variable's chunks are sound.
    const ScalarField salt = io::readField(store, variable("SALT"));
    EXPECT_EQ(salt.dims, ivec3(8, 6, 4));
    EXPECT_THROW_WITH((void)io::describeInput(store), FileError, "cannot read variable 'TEMP'");
}

TEST(Zarr, AMetadataFileIsRefusedNamingItsStoresFolder) {
    const std::string store = test::testData("invalid/invalid_corrupt_chunk.zarr");
    for (const char* name : {".zgroup", ".zattrs", ".zmetadata"}) {
        const std::string file = store + "/" + name;
        EXPECT_EQ(io::zarrStoreOfMetadataFile(file), store);
        EXPECT_THROW_WITH(io::readField(file, variable("SALT")), FormatNotSupported,
                          file + ": a metadata file of a Zarr store, which is read by its folder: " + store);
        EXPECT_THROW_WITH((void)io::describeInput(file), FormatNotSupported, "which is read by its folder: " + store);
    }
    // An array's metadata: its folder, a Zarr v2 array.
    EXPECT_EQ(io::zarrStoreOfMetadataFile(store + "/SALT/.zarray"), store + "/SALT");
    // A chunk, the store itself, a metadata name outside any store: none.
    EXPECT_EQ(io::zarrStoreOfMetadataFile(store + "/SALT/0.0.0"), "");
    EXPECT_EQ(io::zarrStoreOfMetadataFile(store), "");
    test::TempDir tmp;
    std::ofstream(tmp.file(".zattrs")) << "{}";
    EXPECT_EQ(io::zarrStoreOfMetadataFile(tmp.file(".zattrs")), "");
    EXPECT_THROW_WITH(io::readField(tmp.file(".zattrs")), FormatNotSupported, "format not recognised");
}

TEST(Zarr, FoldersWithoutZarrMetadataAreStillDicom) {
    EXPECT_THROW_WITH(io::readField(test::testData("invalid/invalid_no_dicom_images")), FileError, "no DICOM image");
    test::TempDir tmp;
    fs::create_directories(tmp.file("empty"));
    EXPECT_THROW_WITH(io::readField(tmp.file("empty")), InputError, "no DICOM image");
}

TEST(ZarrStore, TellsLayoutsApartFromTheirMetadata) {
    using detail::classifyZarrMetadata;
    using detail::ZarrLayout;
    EXPECT_EQ(classifyZarrMetadata("s", v2Group(R"({"zarr_format": 2})")).description,
              "Zarr v2 store (metadata not consolidated)");
    detail::ZarrMetadata consolidated = v2Group(R"({"zarr_format": 2})");
    consolidated.zmetadata = R"({"metadata": {".zgroup": {"zarr_format": 2}, "a/.zarray": {"zarr_format": 2},
                                 "a/.zattrs": {}, "b/.zarray": {"zarr_format": 2}}, "zarr_consolidated_format": 1})";
    EXPECT_EQ(classifyZarrMetadata("s", consolidated).description,
              "Zarr v2 store (consolidated metadata, .zmetadata: 2 arrays)");
    detail::ZarrMetadata array;
    array.zarray = R"({"zarr_format": 2, "shape": [2]})";
    EXPECT_EQ(classifyZarrMetadata("s", array).description, "Zarr v2 array (metadata not consolidated)");
    detail::ZarrMetadata draft;
    draft.zarrJson = R"({"zarr_format": "https://purl.org/zarr/spec/protocol/core/3.0"})";
    EXPECT_EQ(classifyZarrMetadata("s", draft).layout, ZarrLayout::V3Draft);
    // v2 metadata win over a zarr.json beside them.
    consolidated.zarrJson = R"({"zarr_format": 3, "node_type": "group"})";
    EXPECT_EQ(classifyZarrMetadata("s", consolidated).layout, ZarrLayout::V2);

    detail::ZarrMetadata final3;
    final3.zarrJson = R"({"zarr_format": 3, "node_type": "group"})";
    EXPECT_THROW_WITH(classifyZarrMetadata("dir/s.zarr", final3), FormatNotSupported,
                      "dir/s.zarr: a Zarr v3 store in the final layout");
    EXPECT_THROW_WITH(classifyZarrMetadata("dir/s.zarr/", final3), FormatNotSupported, "to_zarr(\"dir/s_v2.zarr\"");
    EXPECT_THROW_WITH(classifyZarrMetadata("s", v2Group(R"({"zarr_format": 3})")), FormatNotSupported,
                      ".zgroup says \"zarr_format\": 3");
    EXPECT_THROW_WITH(classifyZarrMetadata("s", v2Group("{\"zarr_format\": 2")), FileError, ".zgroup are not valid JSON");
    EXPECT_THROW_WITH(classifyZarrMetadata("s", v2Group("[2]")), FileError, ".zgroup are not a JSON object");
    EXPECT_THROW_WITH(classifyZarrMetadata("s", v2Group("{}")), FileError, ".zgroup have no \"zarr_format\"");
    consolidated.zmetadata = R"({"zarr_consolidated_format": 1})";
    EXPECT_THROW_WITH(classifyZarrMetadata("s", consolidated), FileError, "no \"metadata\" object");
    EXPECT_THROW_WITH(classifyZarrMetadata("s", detail::ZarrMetadata{}), FormatNotSupported, "no Zarr metadata");
}

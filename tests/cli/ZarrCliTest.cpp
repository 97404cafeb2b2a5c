// Zarr stores through the CLI (the stores of tests/ZarrStores.h, made from the Levitus atlas):
// render and slice give the NetCDF file's images byte for byte, info names the store's layout,
// a final-layout v3 store is refused with how to convert it.
#include "../ZarrStores.h"
#include "CliRunner.h"

using namespace octrace::testcli;

TEST(ZarrCli, RenderAndSliceOfAStoreAreTheNetcdfFilesPixelForPixel) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    Scratch s;
    const std::vector<std::string> render = {"--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "7",
                                             "--size", "320x240"};
    const std::vector<std::string> slice = {"--var", "SALT", "--plane", "z", "--at", "500", "--figure"};
    const auto withInput = [](const std::string& command, const std::string& input, std::vector<std::string> args,
                              const std::string& out) {
        args.insert(args.begin(), {command, input});
        args.insert(args.end(), {"-o", out});
        return args;
    };
    Result a = run(withInput("render", levitus, render, s.path("nc.png")));
    ASSERT_EQ(a.code, 0) << a.err;
    Result sa = run(withInput("slice", levitus, slice, s.path("nc_slice.png")));
    ASSERT_EQ(sa.code, 0) << sa.err;
    const std::string netcdf = slurp(s.path("nc.png")), netcdfSlice = slurp(s.path("nc_slice.png"));
    for (const char* store : {"levitus_xr_consolidated.zarr", "levitus_xr_unconsolidated.zarr", "levitus_gdal.zarr",
                              "levitus_missing_chunks.zarr"}) {
        const std::string path = dir + "/" + store;
        Result b = run(withInput("render", path, render, s.path("zarr.png")));
        ASSERT_EQ(b.code, 0) << store << "\n" << b.err;
        EXPECT_TRUE(slurp(s.path("zarr.png")) == netcdf) << store << ": render differs from the NetCDF file's";
        Result sb = run(withInput("slice", path, slice, s.path("zarr_slice.png")));
        ASSERT_EQ(sb.code, 0) << store << "\n" << sb.err;
        EXPECT_TRUE(slurp(s.path("zarr_slice.png")) == netcdfSlice) << store << ": slice differs from the NetCDF file's";
    }
}

TEST(ZarrCli, InfoNamesTheLayoutAndTheVariables) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    Result r = run({"info", dir + "/levitus_missing_chunks.zarr"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* said : {"format: Zarr v2 store (consolidated metadata, .zmetadata: 6 arrays), read through GDAL's Zarr driver",
                             "TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR) Float32 [20 x 180 x 360], units 'DEG C'",
                             "SALT(ZAXLEVITR, YAXLEVITR, XAXLEVITR) Float32 [20 x 180 x 360], units 'PPT'",
                             "sound_speed: derived from TEMP and SALT"})
        EXPECT_NE(r.out.find(said), std::string::npos) << said << "\n" << r.out;
}

TEST(ZarrCli, FinalV3StoreIsRefusedWithHowToConvertIt) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    Scratch s;
    const std::string store = dir + "/levitus_v3.zarr";
    for (const auto& args : {std::vector<std::string>{"render", store, "--var", "TEMP", "-o", s.path("out.png")},
                             std::vector<std::string>{"info", store}}) {
        Result r = run(args);
        EXPECT_EQ(r.code, 1) << r.err;
        EXPECT_NE(r.err.find(store + ": a Zarr v3 store in the final layout"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(".drop_encoding().to_zarr("), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(s.path("out.png")));
}

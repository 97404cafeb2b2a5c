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

// A time series (three months of TEMP over the North Pacific, make_zarr_stores.py) as a store
// and as a NetCDF file: the same steps, dated frames and video.
TEST(ZarrCli, AnimateOfAStoreIsTheNetcdfFilesFrameForFrame) {
    OCTRACE_ZARR_STORES_OR_SKIP(dir, levitus);
    if (std::system("ffprobe -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffprobe absent (Debian package ffmpeg)";
    Scratch s;
    std::vector<std::string> frames[2];
    for (int i = 0; i < 2; ++i) {
        const std::string input = dir + (i == 0 ? "/pacific_monthly.nc" : "/pacific_monthly.zarr");
        const std::string folder = s.path(i == 0 ? "nc" : "zarr");
        std::filesystem::create_directories(folder);
        Result r = run({"animate", input, "--var", "TEMP", "--iso", "10", "--depth", "6", "--time", "all", "--size", "320x240",
                        "--figure", "--frames", folder, "-o", folder + "/out.mp4"});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find("3 frames 320x240 at 12 fps (libx264), steps 2001-01-01 .. 2001-03-01 of 'time'"), std::string::npos)
            << r.err;
        for (int f = 0; f < 3; ++f) frames[i].push_back(slurp(folder + "/frame_000" + std::to_string(f) + ".png"));
        frames[i].push_back(slurp(folder + "/out.mp4"));
    }
    for (std::size_t f = 0; f < 4; ++f) {
        EXPECT_FALSE(frames[1][f].empty()) << f;
        EXPECT_TRUE(frames[0][f] == frames[1][f]) << (f < 3 ? "frame " + std::to_string(f) : std::string("the MP4")) << " differs";
    }
    EXPECT_FALSE(frames[1][0] == frames[1][2]);  // a month later the 10 degree surface has moved
}

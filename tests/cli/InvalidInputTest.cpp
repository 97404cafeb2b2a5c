// Every file of the invalid-input corpus, through the CLI: exit code 1, one line of message
// naming the file and the problem, no output file. The expected substrings are those of
// tests/data/invalid/README.md (reader-level tests check the same messages in detail).
#include "CliRunner.h"

using namespace octrace::testcli;

namespace {
struct Case {
    const char* file;
    const char* var;  // nullptr: no --var
    const char* expect;
};
const Case kCases[] = {
    {"invalid_truncated.nrrd", nullptr, "data truncated"},
    {"invalid_magic.nrrd", nullptr, "not a NRRD file"},
    {"invalid_empty.nrrd", nullptr, "file is empty (0 bytes)"},
    {"invalid_bad_spacing.nhdr", nullptr, "must be positive"},
    {"invalid_missing_data_file.nhdr", nullptr, "no_such_data_file.raw' not found"},
    {"invalid_not_3d.nrrd", nullptr, "expected a 3-D scalar volume"},
    {"invalid_truncated_gzip.nrrd", nullptr, "gzip data truncated"},
    {"invalid_sheared.nrrd", nullptr, "not perpendicular"},
    {"invalid_no_variable.nc", "TEMP", "no variable 'TEMP'"},
    {"invalid_no_variable.nc", nullptr, "no 3-D variable"},
    {"invalid_all_masked.nc", "TEMP", "has no valid sample"},
    {"invalid_formula_terms_missing_variable.nc", "temp", "name variable 'eta' for term 'eta', which the file does not have"},
    {"invalid_formula_terms_malformed.nc", "temp", "is malformed: 'eta' is not of the form 'term:'"},
    {"invalid_formula_terms_shape.nc", "temp", "its dimension 'lat_v' is not one of variable temp(time, sigma, lat, lon)'s"},
    {"invalid_formula_terms_curvilinear_staggered.nc", "temp",
     "h(eta_v, xi_rho): its dimension 'eta_v' is not one of variable temp(ocean_time, s_rho, eta_rho, xi_rho)'s"},
    {"invalid_truncated.nc", nullptr, "NetCDF data truncated"},
    {"invalid_truncated_hdf5.nc", nullptr, "cannot open it"},
    {"invalid_not_netcdf.nc", nullptr, "not a NetCDF file"},
    {"invalid_unknown_format.dat", nullptr, "format not recognised"},
    {"invalid_nul_in_header.nrrd", nullptr, "holds a NUL byte"},
    {"invalid_huge_name_length.nc", nullptr, "NetCDF header is truncated"},
    {"invalid_oversized_gzip.nrrd", nullptr, "gzip data truncated"},
    {"invalid_fewer_files_than_slices.nhdr", nullptr, "one slice per file"},
    {"invalid_no_dicom_images", nullptr, "no DICOM image"},
    {"invalid_not_an_image.dcm", nullptr, "a DICOM file without an image"},
    {"invalid_mixed_sizes", nullptr, "mixed image sizes in one series"},
    {"invalid_volume_slice_counts", nullptr, "volume 1 (temporal position 2) has 4 slices"},
    {"invalid_volume_missing_slice", nullptr, "volume 1 (temporal position 2) is missing a slice"},
    {"invalid_huge_frame_count.dcm", nullptr, "header declares 100000 frame(s)"},
    {"invalid_zero_pixel_spacing.dcm", nullptr, "PixelSpacing 0\\0.5 must be positive"},
    {"invalid_nan_position.dcm", nullptr, "is not 3 finite numbers"},
    {"invalid_length_past_end.dcm", nullptr, "element (0028,1052) DS declares 8456 bytes, only 104 remain in the file"},
    {"invalid_meta_group_only.dcm", nullptr, "the file ends after its file meta group (no data set)"},
    {"invalid_unterminated_fragments.dcm", nullptr, "encapsulated pixel data have no sequence delimitation"},
    {"invalid_vr_mismatch.dcm", nullptr, "element (0028,0103) has VR UI, the DICOM dictionary's is US"},
    {"invalid_enhanced_without_orientation.dcm", nullptr, "multi-frame image with functional groups but no ImageOrientationPatient"},
    {"invalid_tag_order.dcm", nullptr, "element (0028,0103) comes after (FFD8,F4FD)"},
    {"invalid_huge_sizes.nrrd", nullptr, "octrace reads along one axis"},
    {"invalid_too_many_samples.nrrd", nullptr, "exceed the supported 2^32 samples"},
    {"invalid_size_overflow.nrrd", nullptr, "octrace reads along one axis"},
    {"invalid_negative_spacing.nrrd", nullptr, "must be positive"},
    {"invalid_infinite_spacing.nrrd", nullptr, "must be positive"},
    {"invalid_nan_origin.nrrd", nullptr, "is not a finite number"},
    {"invalid_zero_space_direction.nrrd", nullptr, "has zero length"},
    {"invalid_infinite_extent.nrrd", nullptr, "go beyond the supported"},
    {"invalid_tiny_extent.nrrd", nullptr, "too small to place the grid"},
    {"invalid_billion_points.nc", nullptr, "NetCDF data truncated"},
    {"invalid_size_overflow.nc", nullptr, "NetCDF data truncated"},
    {"invalid_billion_points_nc4.nc", nullptr, "octrace reads along one axis"},
    {"invalid_hdf5_memcpy_overlap.nc", nullptr, "corrupt"},
    {"invalid_nan_coordinate.nc", nullptr, "non-finite value"},
    {"invalid_repeated_coordinate.nc", nullptr, "not strictly monotonic"},
    {"invalid_infinite_extent.nc", nullptr, "must be positive and finite"},
    {"invalid_curvilinear_shape.nc", nullptr, "its 2-D coordinate lat(y2, x) is 2 x 4, which is not the shape of two"},
    {"invalid_curvilinear_nan.nc", nullptr, "its 2-D coordinate lon(y, x) is missing or not finite at (1, 2)"},
    {"invalid_curvilinear_latitude.nc", nullptr, "its latitude lat(y, x) is 90.2 at (0, 1), outside -90 .. 90 degrees"},
    {"invalid_key_case.mha", nullptr, "must be spelled 'ElementDataFile'"},
    {"invalid_cr_in_value.mha", nullptr, "control character 0x0D in the header"},
    {"invalid_truncated_zlib.mha", nullptr, "compressed data truncated: 16x16x16 MET_UCHAR need 4096 bytes, the 154 compressed bytes stop after "},
    {"invalid_compressed_size_past_end.mha", nullptr, "holds 309 bytes from byte 196"},
    {"invalid_no_field.nc", nullptr, "no 3-D variable, nor a 2-D one to draw as a map"},
    {"invalid_map_all_masked.nc", nullptr, "a surface needs a 3-D field; draw the 2-D sst with slice"},
    {"invalid_single_image.dcm", nullptr, "a single 4x4 CT image (series 1.2.826.0.1.3680043.9.7777.90): a surface needs a volume"},
    {"invalid_corrupt_chunk.zarr", "TEMP", "cannot read variable 'TEMP' of the Zarr store: Decompression of tile"},
    {"invalid_zarr_v3.zarr", nullptr, "xr.open_zarr("},
};
}  // namespace

TEST(InvalidInput, EveryCorpusFileExitsOneWithItsMessageAndNoOutput) {
    Scratch s;
    for (const Case& c : kCases) {
        const std::string path = std::string(OCTRACE_TEST_DATA) + "/invalid/" + c.file;
        ASSERT_TRUE(std::filesystem::exists(path)) << path;
        std::vector<std::string> args = {"render", path, "-o", s.path("out.png")};
        if (c.var) {
            args.push_back("--var");
            args.push_back(c.var);
        }
        Result r = run(args);
        EXPECT_EQ(r.code, 1) << c.file << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.file << ": expected '" << c.expect << "' in\n" << r.err;
        EXPECT_NE(r.err.find(c.file), std::string::npos) << c.file << ": message does not name the file\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.file << ": not one line\n" << r.err;
        EXPECT_EQ(countEntries(s.dir()), 0) << c.file << " left an output behind";
        // info reports the same problem, exit 1 (a valid file merely lacking a 3-D variable is
        // still described).
        const std::string file = c.file;
        if (!c.var && file != "invalid_no_variable.nc" && file != "invalid_no_field.nc" && file != "invalid_map_all_masked.nc" &&
            file != "invalid_single_image.dcm") {
            Result i = run({"info", path});
            EXPECT_EQ(i.code, 1) << c.file;
        }
    }
}

// NetCDF-4 files on which HDF5 loops (found by fuzz_netcdf_cf): refused after the deadline of
// OCTRACE_HDF5_OPEN_SECONDS (io/src/input/ChildProbe.h), exit 1, one line, no output; `info` too.
TEST(InvalidInput, Netcdf4FilesOnWhichHdf5LoopsAreRefusedAfterTheDeadline) {
    setenv("OCTRACE_HDF5_OPEN_SECONDS", "0.5", 1);
    Scratch s;
    for (const char* file : {"invalid_hdf5_hang_dimension_scales.nc", "invalid_hdf5_hang_2.nc"}) {
        const std::string path = std::string(OCTRACE_TEST_DATA) + "/invalid/" + file;
        for (const auto& args : {std::vector<std::string>{"render", path, "-o", s.path("out.png")},
                                 std::vector<std::string>{"info", path}}) {
            Result r = run(args);
            EXPECT_EQ(r.code, 1) << file << "\n" << r.err;
            EXPECT_NE(r.err.find(path + ": reading the NetCDF-4 (HDF5) metadata did not finish within 0.5 s"),
                      std::string::npos)
                << r.err;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        }
        EXPECT_EQ(countEntries(s.dir()), 0) << file << " left an output behind";
    }
    unsetenv("OCTRACE_HDF5_OPEN_SECONDS");
}

TEST(InvalidInput, IsoValueOutsideTheRangeOfARealFieldExitsOneWithTheRange) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"render", lev, "--var", "TEMP", "--iso", "45", "--region", "120,180,10,60", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("outside the value range"), std::string::npos) << r.err;
    Result v = run({"render", lev, "--var", "PRESSURE", "-o", s.path("x.png")});
    EXPECT_EQ(v.code, 1);
    EXPECT_NE(v.err.find("PRESSURE"), std::string::npos) << v.err;
    Result d = run({"render", lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,95,99", "-o", s.path("x.png")});
    EXPECT_EQ(d.code, 2) << d.err;  // a latitude beyond 90 is a command-line mistake
    EXPECT_EQ(countEntries(s.dir()), 0);
}

// The coastline files of the corpus (README.md, "Coastline files"), given to --coastline of a
// figure: exit 1, one line naming the file, no output; and --coastline without --figure: exit 2.
TEST(InvalidInput, CoastlineFilesExitOneNamingTheFile) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const std::string invalid = std::string(OCTRACE_TEST_DATA) + "/invalid/";
    const std::pair<std::string, const char*> cases[] = {
        {invalid + "invalid_coastline_not_vector.geojson", "OGR cannot open it as vector data"},
        {invalid + "invalid_coastline_points_only.geojson", "no line or polygon in any layer"},
        {invalid + "no_such_coastline.geojson", "no such coastline file"},
    };
    for (const auto& [file, expect] : cases) {
        Result r = run({"slice", lev, "--var", "TEMP", "--plane", "z", "--at", "0", "--figure", "--coastline", file, "-o", s.path("x.png")});
        EXPECT_EQ(r.code, 1) << file << "\n" << r.err;
        EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    Result r = run({"slice", lev, "--var", "TEMP", "--coastline", "low", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("--coastline needs --figure"), std::string::npos) << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);
}

#include "IoTestSupport.h"

#include "octrace/io/FieldReader.h"
#include "octrace/io/NrrdWriter.h"
#include "octrace/util/Error.h"

using namespace octrace;

namespace {

ScalarField smallField() {
    ScalarField f;
    f.name = "blob";
    f.dims = ivec3(12, 3, 2);
    f.values.assign(f.sampleCount(), 1.5f);
    return f;
}

enum class Kind { Input, FormatNotSupported, File, Empty };

bool isKind(const Error& e, Kind k) {
    switch (k) {
        case Kind::FormatNotSupported: return dynamic_cast<const FormatNotSupported*>(&e) != nullptr;
        case Kind::File: return dynamic_cast<const FileError*>(&e) != nullptr;
        case Kind::Empty: return dynamic_cast<const EmptyResultError*>(&e) != nullptr;
        default:
            return dynamic_cast<const InputError*>(&e) && !dynamic_cast<const FileError*>(&e) &&
                   !dynamic_cast<const FormatNotSupported*>(&e) && !dynamic_cast<const EmptyResultError*>(&e);
    }
}

}  // namespace

TEST(FieldReader, MissingFileSaysNoSuchFile) {
    std::string path = test::testData("invalid/does_not_exist.nc");
    EXPECT_THROW_WITH(io::readField(path), InputError, path + ": no such file");
}

TEST(FieldReader, UnknownFormatNamesTheSupportedOnes) {
    EXPECT_THROW_WITH(io::readField(test::testData("invalid/invalid_unknown_format.dat")), FormatNotSupported,
                      "format not recognised (file starts with 'GIF89a\\x01\\x00'); supported: NetCDF");
}

TEST(FieldReader, DispatchesByContentNotByExtension) {
    test::TempDir dir;
    io::NrrdWriter::write(smallField(), dir.file("volume.bin"));
    ScalarField f = io::readField(dir.file("volume.bin"));
    EXPECT_EQ(f.name, "blob");
    EXPECT_EQ(f.dims, ivec3(12, 3, 2));
    ScalarField g = io::readField(test::testData("netcdf/dateline_cf_nc4.nc"));  // HDF5 signature
    EXPECT_EQ(g.name, "temp");
}

TEST(FieldReader, NrrdAcceptsItsOwnNameAndRefusesOthersOrARegion) {
    test::TempDir dir;
    io::NrrdWriter::write(smallField(), dir.file("blob.nrrd"));
    io::FieldRequest r;
    r.variable = "blob";
    EXPECT_EQ(io::readField(dir.file("blob.nrrd"), r).name, "blob");
    r.variable = "TEMP";
    EXPECT_THROW_WITH(io::readField(dir.file("blob.nrrd"), r), InputError, "no variable 'TEMP' (the NRRD volume holds one field, 'blob')");
    r.variable.clear();
    r.hasRegion = true;
    EXPECT_THROW_WITH(io::readField(dir.file("blob.nrrd"), r), InputError, "a region needs a geographic");
}

// Every file of tests/data/invalid through the entry point the CLI uses; the table mirrors
// tests/data/invalid/README.md.
TEST(FieldReader, EveryInvalidCorpusFileFailsWithItsDocumentedMessage) {
    struct Case {
        const char* file;
        const char* variable;
        Kind kind;
        const char* message;
    };
    const Case cases[] = {
        {"invalid_truncated.nrrd", "", Kind::File, "data truncated"},
        {"invalid_magic.nrrd", "", Kind::FormatNotSupported, "not a NRRD file"},
        {"invalid_empty.nrrd", "", Kind::File, "file is empty (0 bytes)"},
        {"invalid_bad_spacing.nhdr", "", Kind::File, "spacing along axis 1 must be positive"},
        {"invalid_missing_data_file.nhdr", "", Kind::File, "not found"},
        {"invalid_not_3d.nrrd", "", Kind::File, "expected a 3-D scalar volume"},
        {"invalid_truncated_gzip.nrrd", "", Kind::File, "gzip data truncated"},
        {"invalid_sheared.nrrd", "", Kind::File, "not perpendicular"},
        {"invalid_no_variable.nc", "TEMP", Kind::Input, "no variable 'TEMP'"},
        {"invalid_no_variable.nc", "", Kind::Input, "no 3-D variable"},
        {"invalid_all_masked.nc", "", Kind::Empty, "has no valid sample"},
        {"invalid_formula_terms_missing_variable.nc", "temp", Kind::Input, "for term 'eta', which the file does not have"},
        {"invalid_formula_terms_malformed.nc", "temp", Kind::Input, "'eta' is not of the form 'term:'"},
        {"invalid_formula_terms_shape.nc", "temp", Kind::Input, "its dimension 'lat_v' is not one of variable temp("},
        {"invalid_formula_terms_curvilinear_staggered.nc", "temp", Kind::Input,
         "its dimension 'eta_v' is not one of variable temp(ocean_time, s_rho, eta_rho, xi_rho)'s"},
        {"invalid_truncated.nc", "", Kind::File, "NetCDF data truncated"},
        {"invalid_truncated_hdf5.nc", "", Kind::File, "GDAL's netCDF driver cannot open it"},
        {"invalid_not_netcdf.nc", "", Kind::FormatNotSupported, "not a NetCDF file"},
        {"invalid_unknown_format.dat", "", Kind::FormatNotSupported, "format not recognised"},
        {"invalid_nul_in_header.nrrd", "", Kind::File, "header line 6 holds a NUL byte"},
        {"invalid_huge_name_length.nc", "", Kind::File, "NetCDF header is truncated"},
        {"invalid_oversized_gzip.nrrd", "", Kind::File, "inflate to at most 29928"},
        {"invalid_fewer_files_than_slices.nhdr", "", Kind::File, "header lists 2 data files for 4 slices"},
        {"invalid_no_dicom_images", "", Kind::File, "no DICOM image"},
        {"invalid_not_an_image.dcm", "", Kind::File, "a DICOM file without an image (no Rows/Columns)"},
        {"invalid_mixed_sizes", "", Kind::File, "mixed image sizes in one series"},
        {"invalid_volume_slice_counts", "", Kind::File, "volume 1 (temporal position 2) has 4 slices, volume 0 (temporal position 1) has 6 slices at other positions"},
        {"invalid_volume_missing_slice", "", Kind::File, "volume 1 (temporal position 2) is missing a slice: it has none at"},
        {"invalid_huge_frame_count.dcm", "", Kind::File, "header declares 100000 frame(s) of 64x64 x 16 bits"},
        {"invalid_single_image.dcm", "", Kind::Input,
         "a single 4x4 CT image (series 1.2.826.0.1.3680043.9.7777.90): a surface needs a volume, a series of slices or a "
         "multi-frame image; draw a single image with slice"},
        {"invalid_zero_pixel_spacing.dcm", "", Kind::File, "PixelSpacing 0\\0.5 must be positive"},
        {"invalid_nan_position.dcm", "", Kind::File, "ImagePositionPatient 'NaN\\0\\1' of frame 2 is not 3 finite numbers"},
        {"invalid_huge_sizes.nrrd", "", Kind::File, "size of axis 0 is 1000000000, more than the 16777216 (2^24)"},
        {"invalid_too_many_samples.nrrd", "", Kind::File, "sizes 4000 x 4000 x 4000 exceed the supported 2^32 samples"},
        {"invalid_size_overflow.nrrd", "", Kind::File, "size of axis 0 is 18446744073709551617, more than"},
        {"invalid_negative_spacing.nrrd", "", Kind::File, "spacing along axis 2 must be positive, is '-2'"},
        {"invalid_infinite_spacing.nrrd", "", Kind::File, "spacing along axis 1 must be positive, is 'inf'"},
        {"invalid_nan_origin.nrrd", "", Kind::File, "'space origin': 'nan' is not a finite number"},
        {"invalid_zero_space_direction.nrrd", "", Kind::File, "space direction of axis 1 has zero length"},
        {"invalid_infinite_extent.nrrd", "", Kind::File, "world bounds 0..inf x 0..7 x 0..7 go beyond the supported +-1e+30"},
        {"invalid_tiny_extent.nrrd", "", Kind::File, "world extent 7e-310 is too small to place the grid"},
        {"invalid_billion_points.nc", "", Kind::File, "the header places data up to byte 16000000116, the file has 132 bytes"},
        {"invalid_size_overflow.nc", "", Kind::File, "the header places data up to byte 18446744073709551615"},
        {"invalid_billion_points_nc4.nc", "", Kind::File, "dimension 'lon' has 1000000000 points, more than the 16777216"},
        {"invalid_nan_coordinate.nc", "", Kind::File, "latitude axis holds a non-finite value"},
        {"invalid_repeated_coordinate.nc", "", Kind::File, "vertical values are not strictly monotonic (0.01 then 0.01"},
        {"invalid_infinite_extent.nc", "", Kind::File, "spacing along axis 0 must be positive and finite, is inf"},
        {"invalid_no_field.nc", "", Kind::Input, "no 3-D variable, nor a 2-D one to draw as a map (variables: temp(depth))"},
        {"invalid_map_all_masked.nc", "", Kind::Input, "a surface needs a 3-D field; draw the 2-D sst with slice"},
        {"invalid_corrupt_chunk.zarr", "TEMP", Kind::File,
         "cannot read variable 'TEMP' of the Zarr store: Decompression of tile"},
        {"invalid_zarr_v3.zarr", "", Kind::FormatNotSupported,
         "a Zarr v3 store in the final layout (zarr.json with \"zarr_format\": 3"},
        {"invalid_curvilinear_shape.nc", "", Kind::File, "variable temp(depth, y, x): its 2-D coordinate lat(y2, x) is 2 x 4, "
         "which is not the shape of two of the variable's dimensions (depth, y, x: 2 x 3 x 4)"},
        {"invalid_curvilinear_nan.nc", "", Kind::File, "its 2-D coordinate lon(y, x) is missing or not finite at (1, 2)"},
        {"invalid_curvilinear_latitude.nc", "", Kind::File, "its latitude lat(y, x) is 90.2 at (0, 1), outside -90 .. 90 degrees"},
    };
    for (const auto& c : cases) {
        std::string path = test::testData(std::string("invalid/") + c.file);
        io::FieldRequest r;
        r.variable = c.variable;
        try {
            io::readField(path, r);
            ADD_FAILURE() << c.file << ": no exception";
        } catch (const Error& e) {
            std::string msg = e.what();
            EXPECT_TRUE(isKind(e, c.kind)) << c.file << ": wrong exception type for '" << msg << "'";
            EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << c.file << ": message does not start with the path: " << msg;
            EXPECT_NE(msg.find(c.message), std::string::npos) << c.file << ": '" << msg << "' lacks '" << c.message << "'";
            EXPECT_EQ(msg.find('\n'), std::string::npos) << c.file << ": message is not one line: " << msg;
        }
    }
}

TEST(FieldReader, DescribeInputCoversNetcdfAndNrrd) {
    std::string nc = io::describeInput(test::testData("netcdf/dateline_cf.nc"));
    EXPECT_NE(nc.find("lon = 72: longitude, units 'degree_east', -177.5 .. 177.5, uniform step 5"), std::string::npos) << nc;
    EXPECT_NE(nc.find("lat = 4: latitude, units 'degrees_north', 30 .. -30, uniform step -20"), std::string::npos) << nc;
    EXPECT_NE(nc.find("temp(time, depth, lat, lon) Float32 [1 x 3 x 4 x 72], units 'degC'"), std::string::npos) << nc;
    EXPECT_NE(nc.find("landmask(lat, lon)"), std::string::npos) << nc;
    EXPECT_NE(nc.find("grid of temp (whole grid):"), std::string::npos) << nc;
    test::TempDir dir;
    io::NrrdWriter::write(smallField(), dir.file("blob.nrrd"));
    std::string nrrd = io::describeInput(dir.file("blob.nrrd"));
    EXPECT_NE(nrrd.find("blob (12 x 3 x 2): valid range 1.5 .. 1.5"), std::string::npos) << nrrd;
}

TEST(FieldReader, ListsTheChoicesOfAnInput) {
    // NetCDF: the variables with three dimensions longer than 1 (a 4-D one counts), not the axes.
    EXPECT_EQ(io::listInputChoices(test::testData("netcdf/dateline_cf.nc")).variables, std::vector<std::string>{"temp"});
    EXPECT_EQ(io::listInputChoices(test::testData("netcdf/dateline_cf_nc4.nc")).variables, std::vector<std::string>{"temp"});
    EXPECT_EQ(io::listInputChoices(test::testData("netcdf/packed_4d.nc")).variables, std::vector<std::string>{"t"});
    EXPECT_TRUE(io::listInputChoices(test::testData("netcdf/packed_4d.nc")).series.empty());
    // A volume format holds one field: nothing to choose.
    test::TempDir dir;
    io::NrrdWriter::write(smallField(), dir.file("blob.nrrd"));
    const io::InputChoices nrrd = io::listInputChoices(dir.file("blob.nrrd"));
    EXPECT_TRUE(nrrd.variables.empty());
    EXPECT_TRUE(nrrd.series.empty());
    std::string missing = test::testData("invalid/does_not_exist.nc");
    EXPECT_THROW(io::listInputChoices(missing), InputError);
}

TEST(FieldReader, ListsTheSeriesOfADicomFolder) {
    const io::InputChoices c = io::listInputChoices(test::testData("dicom/two_series"));
    EXPECT_EQ(c.series.size(), 2u);
    EXPECT_TRUE(c.variables.empty());
}

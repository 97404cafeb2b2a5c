// MetaImage, NIfTI and VTK image data: written from NRRD samples and generated volumes with
// non-trivial origin, spacing and direction, read back through readField().
#include "../FileBytes.h"
#include "IoTestSupport.h"

#include "octrace/io/FieldReader.h"
#include "octrace/io/NrrdReader.h"
#include "octrace/io/VolumeReader.h"
#include "octrace/io/VolumeWriter.h"
#include "octrace/util/Error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

using namespace octrace;

namespace {

const char* kExtensions[] = {".mhd", ".mha", ".nii", ".nii.gz", ".vti"};

// NIfTI keeps its matrices in float32, so positions come back to float precision there.
double positionTolerance(const std::string& ext, const ScalarField& f) {
    if (ext.rfind(".nii", 0) != 0) return 1e-9;
    const Box3 b = f.worldBounds();
    return 4e-7 * std::max(glm::length(b.hi), glm::length(b.lo)) + 1e-6;
}

// A rotation by 30 degrees about (1,2,3) (every column has three non-zero components),
// optionally followed by a mirror of the first axis (a reflection: determinant -1).
dmat3 rotated(bool mirror) {
    dmat3 d(glm::rotate(glm::dmat4(1.0), glm::radians(30.0), glm::normalize(dvec3(1, 2, 3))));
    if (mirror) d[0] = -d[0];
    return d;
}

ScalarField generated() {
    ScalarField f;
    f.name = "density";
    f.dims = ivec3(17, 11, 7);
    f.origin = dvec3(-12.5, 300.25, 7.125);
    f.spacing = dvec3(0.5, 1.25, 3.0);
    f.direction = rotated(false);
    f.values.resize(f.sampleCount());
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 11; ++j)
            for (int i = 0; i < 17; ++i) f.values[f.index(i, j, k)] = float(i + 100 * j + 10000 * k) * 0.5f - 300.0f;
    return f;
}

// Same samples at the same world positions: every sample of `in` maps (through its world
// position) onto the sample of `out` with the same value. `sameOrder` also asks for the same
// storage order (a reader may reverse slices, e.g. NIfTI with qfac -1, and stay right).
void expectSameVolume(const ScalarField& in, const ScalarField& out, double tolerance, const std::string& what,
                      bool sameOrder = true) {
    SCOPED_TRACE(what);
    ASSERT_EQ(in.dims, out.dims);
    ASSERT_EQ(in.values.size(), out.values.size());
    if (sameOrder) {
        EXPECT_TRUE(in.values == out.values) << "samples differ";
    }
    std::size_t misplaced = 0;
    double worst = 0.0;
    for (int k = 0; k < in.dims.z; ++k)
        for (int j = 0; j < in.dims.y; ++j)
            for (int i = 0; i < in.dims.x; ++i) {
                const dvec3 local = glm::transpose(out.direction) * (in.worldFromGrid(i, j, k) - out.origin) / out.spacing;
                const ivec3 n(glm::round(local));
                worst = std::max(worst, glm::length((local - dvec3(n)) * out.spacing));
                if (glm::any(glm::lessThan(n, ivec3(0))) || glm::any(glm::greaterThanEqual(n, out.dims)) ||
                    in.values[in.index(i, j, k)] != out.values[out.index(n.x, n.y, n.z)])
                    ++misplaced;
            }
    EXPECT_EQ(misplaced, 0u) << "samples whose world position holds another value";
    EXPECT_LT(worst, tolerance) << "largest distance between a sample and its original";
}

// With a reflection (determinant -1), VTK's NIfTI reader hands the slices over in reverse order.
void roundTrip(const ScalarField& out, const std::string& name) {
    test::TempDir dir;
    const bool reflection = glm::determinant(out.direction) < 0.0;
    for (const std::string ext : kExtensions) {
        const std::string path = dir.file(name + ext);
        io::VolumeWriter::write(out, path);
        const ScalarField in = io::readField(path);
        expectSameVolume(in, out, positionTolerance(ext, out), path, !(reflection && ext.rfind(".nii", 0) == 0));
    }
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// `values` as the bytes of T in the given byte order.
template <class T>
std::string encode(const std::vector<double>& values, bool bigEndian) {
    std::string out;
    for (double v : values) {
        const T t = static_cast<T>(v);
        char b[sizeof(T)];
        std::memcpy(b, &t, sizeof(T));
        if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
        out.append(b, sizeof(T));
    }
    return out;
}

// `raw` deflated with a zlib header (gzip = false) or a gzip one.
std::string deflated(const std::string& raw, bool gzip) {
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&z, uLong(raw.size())) + 32, '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
    z.avail_in = uInt(raw.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

// A MetaImage header of 5x4x3 samples of `type`, its data in `dataFile`.
std::string metaHeader(const std::string& type, bool bigEndian, bool compressed, const std::string& dataFile,
                       const std::string& extra = "") {
    return "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = " + std::string(bigEndian ? "True" : "False") +
           "\nCompressedData = " + (compressed ? "True" : "False") + "\n" + extra + "DimSize = 5 4 3\nElementType = " + type +
           "\nElementDataFile = " + dataFile + "\n";
}

}  // namespace

TEST(VolumeReader, GeneratedRotatedAnisotropicVolumeRoundTripsInEveryFormat) { roundTrip(generated(), "generated"); }

TEST(VolumeReader, MirroredDirectionRoundTrips) {
    // A reflection: NIfTI keeps it in the sform only (a qform cannot hold it).
    ScalarField f = generated();
    f.direction = rotated(true);
    roundTrip(f, "mirrored");
}

TEST(VolumeReader, NiftiQformAloneAndSformAloneAreHonoured) {
    const ScalarField out = generated();
    test::TempDir dir;
    io::VolumeWriteOptions qformOnly, sformOnly;
    qformOnly.niftiSform = false;
    sformOnly.niftiQform = false;
    io::VolumeWriter::write(out, dir.file("q.nii"), qformOnly);
    io::VolumeWriter::write(out, dir.file("s.nii"), sformOnly);
    const ScalarField q = io::readField(dir.file("q.nii")), s = io::readField(dir.file("s.nii"));
    expectSameVolume(q, out, positionTolerance(".nii", out), "qform only");
    expectSameVolume(s, out, positionTolerance(".nii", out), "sform only");
    EXPECT_NE(q.notes.front().find("qform"), std::string::npos) << q.notes.front();
    EXPECT_NE(s.notes.front().find("sform"), std::string::npos) << s.notes.front();
}

TEST(VolumeReader, InvalidSamplesComeBackInvalid) {
    ScalarField f = generated();
    f.valid.assign(f.sampleCount(), 1);
    f.valid[f.index(3, 4, 5)] = 0;
    test::TempDir dir;
    for (const char* ext : kExtensions) {
        io::VolumeWriter::write(f, dir.file(std::string("holes") + ext));
        const ScalarField in = io::readField(dir.file(std::string("holes") + ext));
        ASSERT_EQ(in.valid.size(), f.sampleCount()) << ext;
        EXPECT_EQ(in.validCount(), f.sampleCount() - 1) << ext;
        EXPECT_FALSE(in.isValid(in.index(3, 4, 5))) << ext;
    }
}

// The real CT samples, moved and turned: every format gives back the NRRD's voxels.
TEST(VolumeReader, ChestCtFromNrrdRoundTripsWithObliqueGeometry) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/lidc2_chest_ct.nrrd");
    ScalarField f = io::NrrdReader::read(path);
    f.origin = dvec3(-180.0, 95.5, -320.25);
    f.direction = rotated(false);
    roundTrip(f, "lidc2");
}

TEST(VolumeReader, HeadFromDetachedNrrdSlicesRoundTrips) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/headsq_raw/quarter.nhdr");
    ScalarField f = io::NrrdReader::read(path);
    f.origin = dvec3(12.0, -7.5, 40.0);
    f.direction = rotated(true);
    roundTrip(f, "headsq");
}

TEST(VolumeReader, MetaImageWrittenByHandFollowsItsTransformMatrix) {
    // 3x2x2 shorts; axis 0 along world y, axis 1 along world -x (ITK order: one axis per triple).
    test::TempDir dir;
    writeText(dir.file("hand.mhd"), "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                                    "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = 10 20 30\nElementSpacing = 0.5 2 4\n"
                                    "DimSize = 3 2 2\nElementType = MET_SHORT\nElementDataFile = hand.raw\n");
    std::vector<std::int16_t> raw(12);
    for (int i = 0; i < 12; ++i) raw[std::size_t(i)] = std::int16_t(i * 10 - 50);
    writeText(dir.file("hand.raw"), std::string(reinterpret_cast<const char*>(raw.data()), raw.size() * 2));
    const ScalarField f = io::readField(dir.file("hand.mhd"));
    ASSERT_EQ(f.dims, ivec3(3, 2, 2));
    for (int i = 0; i < 12; ++i) EXPECT_EQ(f.values[std::size_t(i)], float(i * 10 - 50));  // file order kept
    const dvec3 p = f.worldFromGrid(2, 1, 1);
    EXPECT_NEAR(glm::length(p - dvec3(10.0 - 2.0, 20.0 + 1.0, 30.0 + 4.0)), 0.0, 1e-12);
}

TEST(VolumeReader, DescribeNamesTheFormat) {
    test::TempDir dir;
    const ScalarField f = generated();
    for (const char* ext : kExtensions) io::VolumeWriter::write(f, dir.file(std::string("d") + ext));
    EXPECT_NE(io::describeInput(dir.file("d.mhd")).find("format: MetaImage"), std::string::npos);
    EXPECT_NE(io::describeInput(dir.file("d.nii.gz")).find("format: NIfTI"), std::string::npos);
    EXPECT_NE(io::describeInput(dir.file("d.vti")).find("format: VTK image data"), std::string::npos);
}

TEST(VolumeReader, BrokenFilesAreRefusedWithOneLine) {
    test::TempDir dir;
    const ScalarField f = generated();
    for (const char* ext : kExtensions) io::VolumeWriter::write(f, dir.file(std::string("ok") + ext));
    // Truncated data of each format.
    std::filesystem::resize_file(dir.file("ok.raw"), 100);
    EXPECT_THROW_WITH(io::readField(dir.file("ok.mhd")), FileError, "data truncated");
    std::filesystem::resize_file(dir.file("ok.mha"), 600);
    EXPECT_THROW_WITH(io::readField(dir.file("ok.mha")), FileError, "data truncated");
    std::filesystem::resize_file(dir.file("ok.nii"), 1000);
    EXPECT_THROW_WITH(io::readField(dir.file("ok.nii")), FileError, "NIfTI data truncated");
    std::filesystem::resize_file(dir.file("ok.nii.gz"), 300);
    EXPECT_THROW(io::readField(dir.file("ok.nii.gz")), FileError);
    std::filesystem::resize_file(dir.file("ok.vti"), 700);
    EXPECT_THROW(io::readField(dir.file("ok.vti")), FileError);
    // Headers octrace refuses.
    const std::string head = "ObjectType = Image\nNDims = 3\nDimSize = 3 2 2\nElementType = MET_SHORT\n";
    writeText(dir.file("missing.mhd"), head + "ElementDataFile = nowhere.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("missing.mhd")), FileError, "not found");
    writeText(dir.file("rgb.mhd"), head + "ElementNumberOfChannels = 3\nElementDataFile = ok.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("rgb.mhd")), FileError, "one value per sample");
    writeText(dir.file("flat.mhd"), "NDims = 2\nDimSize = 3 2\nElementType = MET_SHORT\nElementDataFile = ok.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("flat.mhd")), FileError, "3-D");
    writeText(dir.file("list.mhd"), head + "ElementDataFile = LIST\n");
    EXPECT_THROW_WITH(io::readField(dir.file("list.mhd")), FileError, "lists and patterns");
    writeText(dir.file("sheared.mhd"), head + "TransformMatrix = 1 0 0 1 1 0 0 0 1\nElementDataFile = ok.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("sheared.mhd")), FileError, "sheared");
    writeText(dir.file("huge.mha"), "NDims = 3\nDimSize = 16777216 16777216 2\nElementType = MET_DOUBLE\nElementDataFile = LOCAL\nxx");
    EXPECT_THROW_WITH(io::readField(dir.file("huge.mha")), FileError, "data truncated");
    // Found by fuzz_metaimage (long run of 2026-11-25): a key in another case than MetaIO's.
    // octrace took 'ElementDataFIle = LOCAL' for the end of the header, VTK (case-sensitive)
    // read on to a later 'ElementDataFile = L' and leaked its buffers on the missing file.
    EXPECT_THROW_WITH(io::readField(test::testData("invalid/invalid_key_case.mha")), FileError,
                      "key 'ElementDataFIle' must be spelled 'ElementDataFile' (MetaImage keys are case-sensitive)");
    writeText(dir.file("case.mhd"), head + "elementdatafile = ok.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("case.mhd")), FileError, "must be spelled 'ElementDataFile'");
    // Found by a CI smoke run of fuzz_metaimage (2026-11-25): 'ElementDataFile = ' then seven
    // CRs then 'LOCAL'. octrace trimmed the CRs and read LOCAL; MetaIO skips only blanks before
    // a value, looked for a data file named '\r...\rLOCAL' and leaked its buffers.
    EXPECT_THROW_WITH(io::readField(test::testData("invalid/invalid_cr_in_value.mha")), FileError,
                      "control character 0x0D in the header before ElementDataFile (line 'ElementDataFile = ");
    writeText(dir.file("tab.mhd"), head + "Comment = a\vb\nElementDataFile = ok.raw\n");
    EXPECT_THROW_WITH(io::readField(dir.file("tab.mhd")), FileError, "control character 0x0B");
    writeText(dir.file("noise.nii"), std::string(400, 'x'));
    EXPECT_THROW(io::readField(dir.file("noise.nii")), InputError);
    writeText(dir.file("noise.vti"), "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 9");
    EXPECT_THROW(io::readField(dir.file("noise.vti")), InputError);
}

TEST(VolumeReader, CorruptVtiAndNiftiAreRefusedInOneLineWithoutVtksPipelineDump) {
    // Bytes changed in the middle of the compressed data, and the file cut: VTK's reader says
    // what failed, and its pipeline's "Algorithm vtkX(0x...) returned failure for request:
    // vtkInformation (0x...) Debug: Off ..." is left out of the message.
    test::TempDir dir;
    ScalarField f = generated();
    f.dims = ivec3(40, 30, 20);
    f.values.resize(f.sampleCount());
    for (std::size_t i = 0; i < f.values.size(); ++i) f.values[i] = float(std::sin(0.01 * double(i * i % 9973)));
    for (const char* ext : {".vti", ".nii.gz"}) {
        SCOPED_TRACE(ext);
        const std::string good = dir.file(std::string("good") + ext);
        io::VolumeWriter::write(f, good);
        const std::string bytes = testutil::fileBytes(good);
        std::string bad = bytes;
        for (std::size_t i = bad.size() / 2; i < bad.size() / 2 + 64; ++i) bad[i] = char(bad[i] ^ 0x5A);
        writeText(dir.file(std::string("bad") + ext), bad);
        writeText(dir.file(std::string("cut") + ext), bytes.substr(0, bytes.size() * 3 / 4));
        for (const char* stem : {"bad", "cut"}) {
            try {
                io::readField(dir.file(stem + std::string(ext)));
                ADD_FAILURE() << stem << ext << " was read";
            } catch (const FileError& e) {
                const std::string m = e.what();
                EXPECT_EQ(m.find("returned failure"), std::string::npos) << m;
                EXPECT_EQ(m.find("(0x"), std::string::npos) << m;
                EXPECT_EQ(m.find('\n'), std::string::npos) << m;
                EXPECT_NE(m.find(stem + std::string(ext)), std::string::npos) << m;
            }
        }
    }
}

TEST(VolumeReader, MetaImageHeadersWithCrlfTabsAndColonsAreRead) {
    // CRLF line ends, tabs and MetaIO's other separator ':' are plain text: MetaIO reads them
    // as octrace does.
    test::TempDir dir;
    std::string crlf = "ObjectType\t= Image\r\nNDims : 3\r\nDimSize = 4 4 4\r\nElementType = MET_UCHAR\r\nElementDataFile = LOCAL\r\n";
    crlf += std::string(64, '\x07');
    writeText(dir.file("crlf.mha"), crlf);
    const ScalarField crlfField = io::readField(dir.file("crlf.mha"));
    EXPECT_EQ(crlfField.dims, ivec3(4));
    EXPECT_EQ(crlfField.values.back(), 7.0f);
}

TEST(VolumeReader, MetaImageSamplesOfEveryElementTypeAndByteOrderRawZlibAndGzip) {
    // Every element type in both byte orders, raw and compressed: LOCAL zlib without
    // CompressedDataSize (VTK 9.1's MetaIO returned zeros for it), gzip followed by other bytes,
    // detached zlib with CompressedDataSize. Raw MET_LONG_LONG and MET_ULONG_LONG made VTK 9.1's
    // vtkMetaImageReader write past its buffer (valgrind; octrace now decodes the samples).
    test::TempDir dir;
    std::vector<double> values(60);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = double(i * 37 % 250);
    struct Type {
        const char* name;
        std::string (*encode)(const std::vector<double>&, bool);
        double offset, scale;
    };
    const Type types[] = {{"MET_CHAR", encode<std::int8_t>, -125, 1},      {"MET_UCHAR", encode<std::uint8_t>, 0, 1},
                          {"MET_SHORT", encode<std::int16_t>, -125, 100},  {"MET_USHORT", encode<std::uint16_t>, 0, 200},
                          {"MET_INT", encode<std::int32_t>, -125, 1e6},    {"MET_UINT", encode<std::uint32_t>, 0, 1e7},
                          {"MET_FLOAT", encode<float>, -125, 0.25},        {"MET_LONG_LONG", encode<std::int64_t>, -125, 1e3},
                          {"MET_ULONG_LONG", encode<std::uint64_t>, 0, 3}, {"MET_DOUBLE", encode<double>, -125, 1.0 / 64}};
    for (const Type& t : types)
        for (bool big : {false, true}) {
            SCOPED_TRACE(std::string(t.name) + (big ? " big endian" : " little endian"));
            std::vector<double> v(values.size());
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = (values[i] + t.offset) * t.scale;
            const std::string raw = t.encode(v, big);
            writeText(dir.file("raw.raw"), raw);
            writeText(dir.file("raw.mhd"), metaHeader(t.name, big, false, "raw.raw"));
            const std::string zlib = deflated(raw, false);
            writeText(dir.file("local.mha"), metaHeader(t.name, big, true, "LOCAL") + zlib);
            writeText(dir.file("gzip.mha"), metaHeader(t.name, big, true, "LOCAL") + deflated(raw, true) + "trailing bytes");
            writeText(dir.file("detached.zraw"), zlib);
            writeText(dir.file("detached.mhd"),
                      metaHeader(t.name, big, true, "detached.zraw", "CompressedDataSize = " + std::to_string(zlib.size()) + "\n"));
            std::vector<float> expected(v.size());
            for (std::size_t i = 0; i < v.size(); ++i) expected[i] = float(v[i]);
            for (const char* name : {"raw.mhd", "local.mha", "gzip.mha", "detached.mhd"}) {
                const ScalarField f = io::readField(dir.file(name));
                EXPECT_EQ(f.dims, ivec3(5, 4, 3)) << name;
                EXPECT_TRUE(f.values == expected) << name;
            }
        }
}

TEST(VolumeReader, CompressedMetaImageThatIsShortCorruptOrLongIsRefusedNamingTheByte) {
    test::TempDir dir;
    std::vector<double> values(60);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = double(i * i % 1000);
    const std::string zlib = deflated(encode<std::int16_t>(values, false), false);
    const std::string head = metaHeader("MET_SHORT", false, true, "LOCAL");
    // The stream cut short: VTK 9.1's MetaIO printed "Uncompress failed" and returned zeros.
    writeText(dir.file("short.mha"), head + zlib.substr(0, zlib.size() / 2));
    EXPECT_THROW_WITH(io::readField(dir.file("short.mha")), FileError,
                      "compressed data truncated: 5x4x3 MET_SHORT need 120 bytes, the " + std::to_string(zlib.size() / 2) +
                          " compressed bytes stop after ");
    // Every sample there, the end of the stream (its checksum) missing.
    writeText(dir.file("no_end.mha"), head + zlib.substr(0, zlib.size() - 4));
    EXPECT_THROW_WITH(io::readField(dir.file("no_end.mha")), FileError, "stop after 120 without the end of the zlib stream");
    // A stream of fewer samples than DimSize.
    writeText(dir.file("few.mha"), head + deflated(encode<std::int16_t>(std::vector<double>(50, 1.0), false), false));
    EXPECT_THROW_WITH(io::readField(dir.file("few.mha")), FileError, "need 120 bytes, the zlib stream ends after 100");
    // One of more samples.
    writeText(dir.file("many.mha"), head + deflated(encode<std::int16_t>(std::vector<double>(61, 1.0), false), false));
    EXPECT_THROW_WITH(io::readField(dir.file("many.mha")), FileError, "compressed data inflate to more than the 120 bytes of 5x4x3 MET_SHORT");
    // A changed byte in the middle: the checksum, or the stream itself, is wrong.
    std::string bad = zlib;
    bad[bad.size() / 2] = char(bad[bad.size() / 2] ^ 0x55);
    writeText(dir.file("corrupt.mha"), head + bad);
    EXPECT_THROW_WITH(io::readField(dir.file("corrupt.mha")), FileError, "compressed data corrupt after ");
    // CompressedDataSize beyond the file, and compressed data that cannot hold the volume.
    writeText(dir.file("claim.mha"), metaHeader("MET_SHORT", false, true, "LOCAL", "CompressedDataSize = 1000000\n") + zlib);
    EXPECT_THROW_WITH(io::readField(dir.file("claim.mha")), FileError,
                      "CompressedDataSize 1000000 but '" + dir.file("claim.mha") + "' holds " + std::to_string(zlib.size()));
    writeText(dir.file("bomb.mha"), "NDims = 3\nCompressedData = True\nDimSize = 1000 1000 10\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + zlib);
    EXPECT_THROW_WITH(io::readField(dir.file("bomb.mha")), FileError, "deflate expands at most 1032:1");
    writeText(dir.file("word.mha"), metaHeader("MET_SHORT", false, true, "LOCAL", "CompressedDataSize = many\n") + zlib);
    EXPECT_THROW_WITH(io::readField(dir.file("word.mha")), FileError, "CompressedDataSize 'many' is not a finite number");
}

TEST(VolumeReader, MemoryBudgetRefusesBeforeDecoding) {
    test::TempDir dir;
    const ScalarField f = generated();
    io::FieldRequest req;
    req.memoryBudget = 1000;  // the volume needs 1309 samples x 9 bytes
    for (const char* ext : kExtensions) {
        io::VolumeWriter::write(f, dir.file(std::string("b") + ext));
        EXPECT_THROW_WITH(io::readField(dir.file(std::string("b") + ext), req), LimitError, "memory budget");
    }
}

TEST(VolumeReader, SeriesAndRegionAreRefused) {
    test::TempDir dir;
    io::VolumeWriter::write(generated(), dir.file("v.vti"));
    io::FieldRequest req;
    req.series = "1";
    EXPECT_THROW_WITH(io::readField(dir.file("v.vti"), req), InputError, "not DICOM");
}

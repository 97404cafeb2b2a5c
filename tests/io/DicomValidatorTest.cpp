// The DICOM structure walk made before GDCM reads a file (io/src/dicom/DicomValidator.h): every real
// file of ../shared/data/medical passes, every truncation of them is refused cleanly or read,
// and hand-made files exercise each rule (lengths against their container, items and
// delimiters, nesting, transfer syntaxes, layouts without preamble).
#include "../FileBytes.h"
#include "IoTestSupport.h"
#include "../TestScale.h"

#include "dicom/DicomFile.h"
#include "dicom/DicomValidator.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>

using namespace octrace;
using io::detail::validateDicomBytes;

namespace {

std::string le16(std::uint16_t v) { return {char(v & 0xff), char(v >> 8)}; }
std::string le32(std::uint32_t v) { return le16(std::uint16_t(v & 0xffff)) + le16(std::uint16_t(v >> 16)); }
std::string be16(std::uint16_t v) { return {char(v >> 8), char(v & 0xff)}; }
std::string be32(std::uint32_t v) { return be16(std::uint16_t(v >> 16)) + be16(std::uint16_t(v & 0xffff)); }

constexpr std::uint32_t kUndefined = 0xFFFFFFFFu;

bool isLong(const std::string& vr) {
    return vr == "OB" || vr == "OW" || vr == "SQ" || vr == "UN" || vr == "UT" || vr == "OF";
}

/// Explicit VR little endian element header declaring `length`.
std::string head(std::uint16_t g, std::uint16_t e, const std::string& vr, std::uint32_t length) {
    if (isLong(vr)) return le16(g) + le16(e) + vr + std::string(2, '\0') + le32(length);
    return le16(g) + le16(e) + vr + le16(std::uint16_t(length));
}
/// A whole explicit VR little endian element.
std::string el(std::uint16_t g, std::uint16_t e, const std::string& vr, const std::string& value) {
    return head(g, e, vr, std::uint32_t(value.size())) + value;
}
/// Implicit VR little endian element.
std::string iel(std::uint16_t g, std::uint16_t e, const std::string& value) {
    return le16(g) + le16(e) + le32(std::uint32_t(value.size())) + value;
}
std::string item(const std::string& body) { return le16(0xFFFE) + le16(0xE000) + le32(std::uint32_t(body.size())) + body; }
std::string undefinedItem(const std::string& body) {
    return le16(0xFFFE) + le16(0xE000) + le32(kUndefined) + body + le16(0xFFFE) + le16(0xE00D) + le32(0);
}
std::string seqEnd() { return le16(0xFFFE) + le16(0xE0DD) + le32(0); }
std::string undefinedSeq(std::uint16_t g, std::uint16_t e, const std::string& items) {
    return head(g, e, "SQ", kUndefined) + items + seqEnd();
}

const char* kExplicitLE = "1.2.840.10008.1.2.1";

/// Preamble, "DICM" and a meta group declaring `ts`.
std::string part10(const std::string& ts, bool preamble = true) {
    std::string uid = ts;
    if (uid.size() % 2) uid += '\0';
    const std::string body = el(0x0002, 0x0001, "OB", std::string("\0\1", 2)) + el(0x0002, 0x0010, "UI", uid);
    return (preamble ? std::string(128, '\0') + "DICM" : std::string()) + el(0x0002, 0x0000, "UL", le32(std::uint32_t(body.size()))) + body;
}

std::string patient() { return el(0x0010, 0x0010, "PN", "DOE^JOHN"); }

bool validate(const std::string& bytes, std::string& whyNot) {
    return validateDicomBytes(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), "t.dcm", whyNot);
}
bool validate(const std::string& bytes) {
    std::string whyNot;
    return validate(bytes, whyNot);
}

/// Expects a refusal at byte `at` whose message contains `what`.
void expectRefused(const std::string& bytes, std::size_t at, const std::string& what) {
    EXPECT_THROW_WITH(validate(bytes), FileError, "t.dcm: DICOM structure broken at byte " + std::to_string(at) + ": " + what);
}

std::string slurp(const std::string& path) { return testutil::fileBytes(path); }

/// Every file under ../shared/data/medical with the DICOM preamble.
std::vector<std::string> realDicomFiles() {
    std::vector<std::string> files;
    const std::string root = test::sharedData("medical");
    if (root.empty()) return files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        const std::string head = slurp(e.path().string()).substr(0, 132);
        if (head.size() == 132 && head.compare(128, 4, "DICM") == 0) files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

TEST(DicomValidator, PassesEveryRealDicomFileIncludingTheCompressedOnes) {
    const std::vector<std::string> files = realDicomFiles();
    if (files.empty()) GTEST_SKIP() << "shared data absent: " << OCTRACE_SHARED_DATA << "/medical";
    EXPECT_GE(files.size(), 30u);
    for (const std::string& f : files) {
        std::string whyNot;
        // The truncated JPEG 2000 file lacks the 8 bytes of its pixel data's sequence
        // delimitation: its fragments are whole, so only that is refused (GDCM would read on
        // and fail to decode it; without the delimitation a shorter cut makes GDCM assert).
        if (f.find("too_short") != std::string::npos) {
            EXPECT_THROW_WITH(io::detail::validateDicomFile(f, whyNot), FileError,
                              f + ": DICOM structure broken at byte 40316: encapsulated pixel data have no sequence "
                                  "delimitation (FFFE,E0DD) before the end of the file");
            continue;
        }
        EXPECT_NO_THROW(EXPECT_TRUE(io::detail::validateDicomFile(f, whyNot)) << f << ": " << whyNot) << f;
    }
}

// Truncated at many offsets (every byte of the first 2 KiB, then 200 offsets spread over the
// rest): the walk refuses the cut with a FileError or passes it, and a cut that passes (it
// falls between two elements) is read and decoded by GDCM without a crash: a FileError or a
// result, nothing else.
TEST(DicomValidator, EveryTruncationOfTheRealFilesIsRefusedCleanlyOrRead) {
    const std::vector<std::string> files = realDicomFiles();
    if (files.empty()) GTEST_SKIP() << "shared data absent: " << OCTRACE_SHARED_DATA << "/medical";
    test::TempDir dir;
    std::size_t refused = 0, passed = 0, read = 0;
    for (const std::string& f : files) {
        const std::string bytes = slurp(f);
        // Every cut inside the first 2048 bytes (the preamble, the meta group and the first data
        // elements), fewer under OCTRACE_TEST_SCALE (the sanitizer run: 410 at 0.2, still past the
        // meta group; fuzz_dicom explores the rest).
        const auto dense = std::size_t(testutil::scaledCount(2048, 256));
        std::vector<std::size_t> cuts;
        for (std::size_t n = 0; n < std::min(bytes.size(), dense); ++n) cuts.push_back(n);
        for (std::size_t k = 1; k <= 200; ++k) cuts.push_back(bytes.size() * k / 201);
        cuts.push_back(bytes.size() - 1);
        for (std::size_t n : cuts) {
            const std::string cut = bytes.substr(0, n);
            std::string whyNot;
            bool ok = false;
            try {
                ok = validate(cut, whyNot);
            } catch (const FileError& e) {
                ++refused;
                EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
                continue;
            }
            if (!ok) {
                EXPECT_EQ(whyNot.rfind("not a DICOM file", 0), 0u) << f << " cut at " << n << ": " << whyNot;
                continue;
            }
            ++passed;
            const std::string path = dir.file("cut.dcm");
            std::ofstream(path, std::ios::binary).write(cut.data(), std::streamsize(cut.size()));
            try {
                std::string why;
                if (auto h = io::detail::readDicomHeader(path, why)) {
                    (void)io::detail::decodeDicomFrames(*h);
                    ++read;
                }
            } catch (const Error&) {
                // A clean refusal.
            } catch (const std::exception& e) {
                ADD_FAILURE() << f << " cut at " << n << ": " << e.what();
            }
        }
    }
    EXPECT_GT(refused, 10000u);
    EXPECT_GT(passed, 0u);
    (void)read;
}

TEST(DicomValidator, AcceptsNestedSequencesOfDefinedAndUndefinedLength) {
    const std::string inner = el(0x0020, 0x0032, "DS", "0\\0\\1 ");
    const std::string defined = el(0x5200, 0x9229, "SQ", item(el(0x0020, 0x9116, "SQ", item(inner))));
    const std::string undefined = undefinedSeq(0x5200, 0x9230, undefinedItem(undefinedSeq(0x0020, 0x9113, undefinedItem(inner))) + item(inner));
    EXPECT_TRUE(validate(part10(kExplicitLE) + patient() + defined + undefined));
    EXPECT_TRUE(validate(part10(kExplicitLE) + patient() + undefinedSeq(0x0008, 0x1140, "")));  // empty sequence
    // GDCM asserts when the file ends right after the meta group.
    expectRefused(part10(kExplicitLE), part10(kExplicitLE).size(), "the file ends after its file meta group (no data set)");
}

TEST(DicomValidator, RefusesTheGdcmAbortReproducerALengthRunningPastTheEndOfTheFile) {
    const std::string start = part10(kExplicitLE) + patient();
    // A RescaleIntercept declaring 8,456 bytes where 8 follow (found by fuzz_dicom).
    const std::string bytes = start + head(0x0028, 0x1052, "DS", 8456) + "-1024.0 ";
    expectRefused(bytes, start.size(), "element (0028,1052) DS declares 8456 bytes, only 8 remain in the file");
    // The same in a 32-bit length.
    expectRefused(start + head(0x7FE0, 0x0010, "OW", 0x7FFFFFFE) + "ab", start.size(),
                  "element (7FE0,0010) OW declares 2147483646 bytes, only 2 remain in the file");
}

TEST(DicomValidator, RefusesElementsBelowThePixelDataTagAfterOnesPastIt) {
    // GDCM reads a header up to the first top-level tag at or past (7FE0,0010): an element below
    // it that comes after one past it is hidden from the header but not from the image reader
    // (found by fuzz_dicom: functional groups after (FFD8,F4FD), and GDCM asserted).
    const std::string start = part10(kExplicitLE) + patient();
    const std::string late = el(0xFFD8, 0xF4FD, "US", le16(15));
    expectRefused(start + late + el(0x0028, 0x0103, "US", le16(0)), start.size() + late.size(),
                  "element (0028,0103) comes after (FFD8,F4FD): elements below the pixel data (7FE0,0010) must come before those at or past it (ascending tag order)");
    expectRefused(start + el(0x7FE0, 0x0010, "OW", "abcd") + patient(), start.size() + 12 + 4, "element (0010,0010) comes after (7FE0,0010)");
    // Disorder below the pixel data GDCM sorts out itself, and elements past it in any order
    // after it (trailing padding) are let through; so is disorder inside items.
    EXPECT_TRUE(validate(start + el(0x0008, 0x0060, "CS", "CT") + el(0x7FE0, 0x0010, "OW", "abcd") + el(0xFFFC, 0xFFFC, "OB", "xx")));
    EXPECT_TRUE(validate(start + el(0x0008, 0x1140, "SQ", item(patient() + el(0x0008, 0x0060, "CS", "CT")))));
    EXPECT_TRUE(validate(start + el(0xFFFC, 0xFFFC, "OB", "xx") + el(0x7FE0, 0x0010, "OW", "abcd")));
    expectRefused(slurp(test::testData("invalid/invalid_tag_order.dcm")), 422, "element (0028,0103) comes after (FFD8,F4FD)");
}

TEST(DicomValidator, ChecksEveryLengthAgainstItsEnclosingItemAndSequence) {
    const std::string start = part10(kExplicitLE) + patient();
    // An element longer than its item (the file goes on after it).
    const std::string inItem = el(0x0020, 0x0032, "DS", "0\\0\\1 ");
    std::string bytes = start + el(0x0008, 0x1140, "SQ", item(head(0x0020, 0x0032, "DS", 10) + "0\\0\\1 ")) + patient();
    expectRefused(bytes, start.size() + 12 + 8, "element (0020,0032) DS declares 10 bytes, only 6 remain in its item");
    // An item longer than its sequence.
    const std::string seqHead = head(0x0008, 0x1140, "SQ", 8 + std::uint32_t(inItem.size()));
    bytes = start + seqHead + le16(0xFFFE) + le16(0xE000) + le32(std::uint32_t(inItem.size()) + 2) + inItem + patient();
    expectRefused(bytes, start.size() + 12, "item of sequence (0008,1140) declares 16 bytes, only 14 remain in its sequence");
    // A sequence longer than the file.
    bytes = start + head(0x0008, 0x1140, "SQ", 100) + item(inItem);
    expectRefused(bytes, start.size(), "element (0008,1140) SQ declares 100 bytes, only 22 remain in the file");
}

TEST(DicomValidator, RefusesOddLengthsBadItemTagsAndMissingDelimiters) {
    const std::string start = part10(kExplicitLE) + patient();
    expectRefused(start + el(0x0010, 0x0020, "LO", "ABC"), start.size(), "element (0010,0020) LO has an odd length (3)");
    // An element where an item is expected.
    expectRefused(start + undefinedSeq(0x0008, 0x1140, patient()), start.size() + 12,
                  "sequence (0008,1140) holds (0010,0010) where an item (FFFE,E000) was expected");
    // An item tag where an element is expected.
    expectRefused(start + item(patient()), start.size(), "item tag (FFFE,E000) where a data element was expected");
    // A sequence delimitation with a length.
    const std::string badEnd = head(0x0008, 0x1140, "SQ", kUndefined) + le16(0xFFFE) + le16(0xE0DD) + le32(4) + "abcd";
    expectRefused(start + badEnd, start.size() + 12, "sequence delimitation (FFFE,E0DD) has length 4 (must be 0)");
    // An undefined-length item and sequence that never end.
    expectRefused(start + head(0x0008, 0x1140, "SQ", kUndefined) + le16(0xFFFE) + le16(0xE000) + le32(kUndefined) + patient(),
                  start.size() + 12 + 8 + 16, "item of undefined length has no item delimitation (FFFE,E00D) before the end of the file");
    expectRefused(start + head(0x0008, 0x1140, "SQ", kUndefined) + item(patient()), start.size() + 12 + 24,
                  "sequence (0008,1140) of undefined length has no sequence delimitation (FFFE,E0DD)");
    // Undefined length on a VR that cannot have one, an unknown VR, bytes after the last element.
    expectRefused(start + head(0x0010, 0x4000, "UT", kUndefined), start.size(),
                  "element (0010,4000) UT has an undefined length (only sequences and encapsulated pixel data may)");
    expectRefused(start + le16(0x0010) + le16(0x0020) + "ZZ" + le16(2) + "AB", start.size(),
                  "element (0010,0020) has an unknown VR 'ZZ'");
    expectRefused(start + std::string("\x10\x00", 2), start.size(), "2 byte(s) left in the file, too few for an element header");
}

TEST(DicomValidator, BoundsTheNestingDepthOfSequences) {
    auto nested = [](int depth) {
        std::string open, close;
        for (int d = 0; d < depth; ++d) {
            open += head(0x0040, 0xA730, "SQ", kUndefined) + le16(0xFFFE) + le16(0xE000) + le32(kUndefined);
            close += le16(0xFFFE) + le16(0xE00D) + le32(0) + seqEnd();
        }
        return open + patient() + close;
    };
    const std::string start = part10(kExplicitLE);
    EXPECT_TRUE(validate(start + nested(io::detail::kMaxDicomSequenceDepth)));
    EXPECT_THROW_WITH(validate(start + nested(io::detail::kMaxDicomSequenceDepth + 1)), FileError,
                      "sequences nested deeper than 32");
    // Far deeper than the stack could take if the walk did not stop: refused just the same.
    EXPECT_THROW_WITH(validate(start + nested(100000)), FileError, "sequences nested deeper than 32");
}

TEST(DicomValidator, WalksEncapsulatedPixelDataFragmentByFragment) {
    const std::string start = part10("1.2.840.10008.1.2.4.70") + patient();
    const std::string frags = item("") + item(std::string(10, 'j'));
    EXPECT_TRUE(validate(start + head(0x7FE0, 0x0010, "OB", kUndefined) + frags + seqEnd()));
    expectRefused(start + head(0x7FE0, 0x0010, "OB", kUndefined) + frags, start.size() + 12 + 8 + 18,
                  "encapsulated pixel data have no sequence delimitation (FFFE,E0DD) before the end of the file");
    expectRefused(start + head(0x7FE0, 0x0010, "OB", kUndefined) + le16(0xFFFE) + le16(0xE000) + le32(64) + "jj" + seqEnd(),
                  start.size() + 12, "a pixel data fragment declares 64 bytes, only 10 remain in the file");
    expectRefused(start + head(0x7FE0, 0x0010, "OB", kUndefined) + patient() + seqEnd(), start.size() + 12,
                  "encapsulated pixel data hold (0010,0010) where a fragment item (FFFE,E000) was expected");
}

namespace {
/// A JPEG marker segment: FF, the marker, the length (itself included) and the parameters.
std::string jpegSegment(unsigned marker, const std::string& params) {
    return std::string{char(0xFF), char(marker)} + be16(std::uint16_t(params.size() + 2)) + params;
}
/// A JPEG stream of `nf` components at `precision` bits: SOI, `beforeSof`, DQT, SOFn, SOS, a few
/// bytes of scan and EOI (even length, as a fragment must be).
std::string jpegStream(unsigned sof = 0xC1, int precision = 12, int nf = 1, const std::string& beforeSof = "",
                       const std::string& afterDqt = "") {
    std::string components;
    for (int c = 0; c < nf; ++c) components += std::string{char(c + 1), char(0x11), char(0)};
    const std::string sofParams = std::string(1, char(precision)) + be16(4) + be16(4) + std::string(1, char(nf)) + components;
    std::string s = std::string{char(0xFF), char(0xD8)} + beforeSof + jpegSegment(0xDB, std::string(65, '\x01')) + afterDqt +
                    jpegSegment(sof, sofParams) + jpegSegment(0xDA, std::string{char(1), char(1), char(0), char(0), char(63), char(0)}) +
                    "scan" + std::string{char(0xFF), char(0xD9)};
    if (s.size() % 2) s.insert(s.size() - 2, 1, '\0');
    return s;
}
}  // namespace

TEST(DicomValidator, ChecksTheHeaderOfEveryJpegFrameAsGdcmsJpegCodecsReadIt) {
    // GDCM reads a JPEG frame's header with the IJG library and asserts (aborting the process)
    // when the library warns there (found by fuzz_dicom: garbage after a DQT segment of the
    // real JPEG-lossy.dcm) and on values it does not handle.
    const std::string start = part10("1.2.840.10008.1.2.4.51") + patient();
    const std::string pixels = head(0x7FE0, 0x0010, "OB", kUndefined) + item("");
    const std::size_t frame = start.size() + pixels.size() + 8;  // the stream's first byte
    const auto file = [&](const std::string& jpeg, const std::string& ts = "1.2.840.10008.1.2.4.51") {
        return part10(ts) + patient() + pixels + item(jpeg) + seqEnd();
    };
    EXPECT_TRUE(validate(file(jpegStream())));
    EXPECT_TRUE(validate(file(jpegStream(0xC3, 16)))) << "lossless, 16 bits";
    EXPECT_TRUE(validate(file(jpegStream(0xC0, 8, 3, jpegSegment(0xEE, std::string("Adobe") + std::string(6, '\0') + '\x01')))))
        << "3 components, Adobe transform 1 (YCbCr)";
    EXPECT_TRUE(validate(file(jpegStream(0xC1, 12, 1, "", std::string(3, char(0xFF)))))) << "fill bytes before a marker";
    const std::size_t sofAt = frame + 2 + 69;  // after SOI and the DQT segment
    expectRefused(file(jpegStream(0xC1, 12, 1, "", "junk")), sofAt,
                  "a JPEG frame's header holds bytes other than a marker between its segments");
    expectRefused(file(jpegStream(0xC1, 10)), sofAt, "JPEG frame header FFC1 declares a sample precision of 10 bits");
    expectRefused(file(jpegStream(0xC1, 12, 2)), sofAt, "JPEG frame of 2 components (1, 3 or 4 are read)");
    expectRefused(file(jpegStream(0xC9)), sofAt, "JPEG frame coded by FFC9 (hierarchical or arithmetic)");
    const std::string jfif2 = jpegSegment(0xE0, std::string("JFIF") + '\0' + "\x02\x01" + std::string(7, '\0'));
    expectRefused(file(jpegStream(0xC1, 12, 1, jfif2)), frame + 2, "JPEG frame with a JFIF segment of version 2.1 (1.x is read)");
    const std::string adobe2 = jpegSegment(0xEE, std::string("Adobe") + std::string(6, '\0') + '\x02');
    expectRefused(file(jpegStream(0xC0, 8, 3, adobe2)), sofAt + 16 + 19,
                  "JPEG frame of 3 components with Adobe colour transform 2 (0 or 1 is read)");
    // Cut before its scan: the fragment ends inside the SOF segment.
    expectRefused(file(jpegStream().substr(0, 2 + 69 + 7)), sofAt, "JPEG marker segment FFC1 declares 11 bytes, 5 remain in its fragment");
    expectRefused(file(jpegStream().substr(0, 2 + 69 + 1)), frame, "a JPEG frame's fragment ends before its scan");  // FF of SOF
    const std::string eoiFirst = std::string{char(0xFF), char(0xD8), char(0xFF), char(0xD9)};
    expectRefused(file(eoiFirst), frame + 2, "a JPEG frame's header holds EOI before its scan");
    // Other codecs' streams are not JPEG (JPEG 2000 here): not looked into.
    EXPECT_TRUE(validate(file(jpegStream(0xC1, 12, 1, "", "junk"), "1.2.840.10008.1.2.4.90")));
    // The fuzzer's finding itself.
    expectRefused(slurp(test::testData("invalid/invalid_jpeg_garbage_in_header.dcm")), 3090,
                  "a JPEG frame's header holds bytes other than a marker between its segments");
}

TEST(DicomValidator, WalksImplicitVrLittleEndianIncludingItsSequences) {
    const std::string start = part10("1.2.840.10008.1.2") + iel(0x0010, 0x0010, "DOE^JOHN");
    const std::string nestedItem = item(iel(0x0020, 0x0032, "0\\0\\1 "));
    // Undefined length: a sequence; defined length starting with an item: walked as one too.
    const std::string undefinedSq = le16(0x5200) + le16(0x9230) + le32(kUndefined) + undefinedItem(iel(0x0020, 0x0013, "1 ")) + seqEnd();
    EXPECT_TRUE(validate(start + iel(0x0008, 0x1140, nestedItem) + undefinedSq + iel(0x7FE0, 0x0010, "abcd")));
    std::string broken = nestedItem;
    broken[8 + 4] = 20;  // the inner element's length: 20 bytes in an item of 14
    expectRefused(start + iel(0x0008, 0x1140, broken), start.size() + 16,
                  "element (0020,0032) declares 20 bytes, only 6 remain in its item");
    expectRefused(start + le16(0x7FE0) + le16(0x0010) + le32(kUndefined) + seqEnd(), start.size(),
                  "element (7FE0,0010) has an undefined length");
}

TEST(DicomValidator, WalksExplicitVrBigEndianWithItsOwnByteOrder) {
    const std::string start = part10("1.2.840.10008.1.2.2");
    const std::string name = be16(0x0010) + be16(0x0010) + "PN" + be16(8) + "DOE^JOHN";
    const std::string pixels = be16(0x7FE0) + be16(0x0010) + "OW" + std::string(2, '\0') + be32(4) + "abcd";
    EXPECT_TRUE(validate(start + name + pixels));
    // The same file read as little endian would be broken: its meta group says big endian.
    EXPECT_THROW_WITH(validate(part10(kExplicitLE) + name + pixels), FileError, "t.dcm: DICOM structure broken");
    const std::string tooLong = be16(0x0010) + be16(0x0010) + "PN" + be16(80) + "DOE^JOHN";
    expectRefused(start + tooLong, start.size(), "element (0010,0010) PN declares 80 bytes, only 8 remain in the file");
}

TEST(DicomValidator, RefusesDeflatedUnknownAndMissingTransferSyntaxes) {
    EXPECT_THROW_WITH(validate(part10("1.2.840.10008.1.2.1.99") + "x"), FileError,
                      "transfer syntax 1.2.840.10008.1.2.1.99 (deflated) is not supported");
    EXPECT_THROW_WITH(validate(part10("1.2.3.4") + patient()), FileError, "transfer syntax '1.2.3.4' is not one octrace reads");
    EXPECT_THROW_WITH(validate(part10("1.2.840.10008.1.2.4.201") + patient()), FileError, "is not one octrace reads");
    const std::string version = el(0x0002, 0x0001, "OB", std::string("\0\1", 2));
    const std::string noTs = std::string(128, '\0') + "DICM" + el(0x0002, 0x0000, "UL", le32(14)) + version + patient();
    expectRefused(noTs, 132 + 12 + 14, "the file meta group has no TransferSyntaxUID (0002,0010)");
    expectRefused(std::string(128, '\0') + "DICM" + version + patient(), 132,
                  "the file meta group does not start with its group length (0002,0000) UL");
    expectRefused(part10(kExplicitLE) + el(0x0002, 0x0100, "SQ", "") + patient(), part10(kExplicitLE).size(),
                  "element (0002,0100) of the file meta group has VR SQ");
    expectRefused(std::string(128, '\0') + "DICM" + patient(), 132, "no file meta group (0002,xxxx) after 'DICM'");
}

TEST(DicomValidator, AcceptsFilesWithoutPreambleAsGdcmDoesAndTellsOtherBytesAreNotDicom) {
    EXPECT_TRUE(validate(part10(kExplicitLE, false) + patient()));
    EXPECT_TRUE(validate(iel(0x0008, 0x0060, "CT") + iel(0x0010, 0x0010, "DOE^JOHN")));  // bare implicit data set
    std::string whyNotBare;
    EXPECT_FALSE(validate(iel(0x0010, 0x0010, "DOE^JOHN"), whyNotBare)) << "GDCM guesses other groups; so do we not";
    EXPECT_TRUE(validate(el(0x0008, 0x0060, "CS", "CT") + patient()));                    // bare explicit data set
    std::string whyNot;
    EXPECT_FALSE(validate("this is not DICOM at all", whyNot));
    EXPECT_EQ(whyNot, "not a DICOM file (no 'DICM' at byte 128, no DICOM element at its start)");
    EXPECT_FALSE(validate("", whyNot));
    // Starts like a bare data set, but its first element runs past the end.
    EXPECT_THROW_WITH(validate(iel(0x0008, 0x0060, "CT").substr(0, 9)), FileError, "declares 2 bytes, only 1 remain");
}

TEST(DicomValidator, WalksHundredsOfThousandsOfElementsAndItemsInOnePass) {
    std::string items;
    for (int i = 0; i < 100000; ++i) items += item(el(0x0008, 0x1150, "UI", "1.23"));
    std::string frags;
    for (int i = 0; i < 100000; ++i) frags += item("ab");
    EXPECT_TRUE(validate(part10("1.2.840.10008.1.2.4.50") + el(0x0008, 0x1140, "SQ", items) +
                         head(0x7FE0, 0x0010, "OB", kUndefined) + frags + seqEnd()));
}

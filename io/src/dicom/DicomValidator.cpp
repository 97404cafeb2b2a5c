#include "dicom/DicomValidator.h"

#include "octrace/util/Error.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string_view>

namespace octrace::io::detail {
namespace {

constexpr std::uint32_t kUndefinedLength = 0xFFFFFFFFu;
constexpr std::uint16_t kItemGroup = 0xFFFE;
constexpr std::uint16_t kItem = 0xE000, kItemEnd = 0xE00D, kSequenceEnd = 0xE0DD;

struct Syntax {
    bool explicitVr = true;
    bool bigEndian = false;
};
constexpr Syntax kExplicitLittle{true, false}, kImplicitLittle{false, false}, kExplicitBig{true, true};

// PS3.5 6.2: every VR; those of the second list have a 32-bit length (PS3.5 7.1.2).
constexpr std::string_view kShortVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD", "IS", "LO",
                                          "LT", "PN", "SH", "SL", "SS", "ST", "TM", "UI", "UL", "US"};
constexpr std::string_view kLongVrs[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};

template <std::size_t N>
bool among(std::string_view text, const std::string_view (&list)[N]) {
    for (std::string_view v : list)
        if (v == text) return true;
    return false;
}
bool isVr(std::string_view vr) { return among(vr, kShortVrs) || among(vr, kLongVrs); }

constexpr std::uint32_t kPixelDataTag = 0x7FE00010u;

std::string tagName(std::uint16_t group, std::uint16_t element) {
    char text[16];
    std::snprintf(text, sizeof text, "(%04X,%04X)", group, element);
    return text;
}

std::string printableVr(std::string_view vr) {
    std::string out = "'";
    for (char c : vr) {
        if (c >= 0x20 && c < 0x7f) {
            out += c;
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(c));
            out += hex;
        }
    }
    return out + "'";
}

// Where a walk may go: up to `end`, which is the end of `what` ("the file", "its item"...).
struct Container {
    std::size_t end;
    const char* what;
};

struct Parsed {
    std::size_t valueAt;  ///< first byte of the value
    std::size_t next;     ///< first byte after the element (after its delimiter when undefined)
};

class Walker {
public:
    Walker(const std::uint8_t* data, std::size_t size, const std::string& name) : d_(data), size_(size), name_(name) {}

    [[noreturn]] void fail(std::size_t at, const std::string& what) const {
        throw FileError(name_ + ": DICOM structure broken at byte " + std::to_string(at) + ": " + what);
    }

    std::uint16_t u16(std::size_t at, bool big) const {
        return big ? std::uint16_t(d_[at] << 8 | d_[at + 1]) : std::uint16_t(d_[at] | d_[at + 1] << 8);
    }
    std::uint32_t u32(std::size_t at, bool big) const {
        const std::uint32_t a = u16(at, big), b = u16(at + 2, big);
        return big ? a << 16 | b : b << 16 | a;
    }
    std::string_view bytes(std::size_t at, std::size_t n) const { return {reinterpret_cast<const char*>(d_ + at), n}; }
    std::size_t size() const { return size_; }
    /// The pixel data's fragments are JPEG streams that GDCM decodes with the IJG library:
    /// their headers are checked too (jpegHeader).
    void setJpegFragments(bool on) { jpeg_ = on; }

    /// Elements from `at` to the container's end, or (`delimited`: an item of undefined length)
    /// up to and including the item delimitation. Returns where the walk ended.
    std::size_t dataSet(std::size_t at, Container c, Syntax s, int depth, bool delimited) const {
        std::size_t p = at;
        std::uint32_t pastPixelData = 0;  // the first top-level tag at or past (7FE0,0010), 0: none yet
        for (;;) {
            if (p == c.end) {
                if (delimited)
                    fail(p, std::string("item of undefined length has no item delimitation (FFFE,E00D) before the end of ") + c.what);
                return p;
            }
            if (c.end - p < 8)
                fail(p, std::to_string(c.end - p) + " byte(s) left in " + c.what + ", too few for an element header");
            const std::uint16_t group = u16(p, s.bigEndian), element = u16(p + 2, s.bigEndian);
            if (group == kItemGroup) {
                if (delimited && element == kItemEnd) {
                    if (const std::uint32_t n = u32(p + 4, s.bigEndian); n != 0)
                        fail(p, "item delimitation (FFFE,E00D) has length " + std::to_string(n) + " (must be 0)");
                    return p + 8;
                }
                fail(p, std::string("item tag ") + tagName(group, element) + " where a data element was expected");
            }
            // The standard orders a data set's elements by ascending tag. GDCM reads a header up
            // to the pixel data by stopping at the first top-level tag at or past (7FE0,0010), so
            // an element below that tag after one past it is hidden from the header and not from
            // the image reader (fuzz_dicom: functional groups after (FFD8,F4FD) reached an
            // assertion). Other disorder GDCM sorts out, and is let through.
            const std::uint32_t tag = std::uint32_t(group) << 16 | element;
            if (depth == 0 && pastPixelData && tag < kPixelDataTag)
                fail(p, std::string("element ") + tagName(group, element) + " comes after " +
                            tagName(std::uint16_t(pastPixelData >> 16), std::uint16_t(pastPixelData & 0xFFFF)) +
                            ": elements below the pixel data (7FE0,0010) must come before those at or past it (ascending tag order)");
            if (depth == 0 && !pastPixelData && tag >= kPixelDataTag) pastPixelData = tag;
            p = this->element(p, c, s, depth).next;
        }
    }

    /// One element at `at` (its tag read, not an item tag), its value walked when it is a
    /// sequence or encapsulated pixel data.
    Parsed element(std::size_t at, Container c, Syntax s, int depth) const {
        const std::uint16_t group = u16(at, s.bigEndian), elem = u16(at + 2, s.bigEndian);
        const bool pixelData = group == 0x7FE0 && elem == 0x0010;
        std::string what = std::string("element ") + tagName(group, elem);
        std::string_view vr;
        std::uint32_t length = 0;
        std::size_t valueAt = at + 8;
        if (s.explicitVr) {
            vr = bytes(at + 4, 2);
            what += ' ';
            what += vr;
            if (among(vr, kLongVrs)) {
                if (c.end - at < 12)
                    fail(at, what + ": " + std::to_string(c.end - at) + " byte(s) left in " + c.what +
                                 ", too few for its 12-byte header");
                length = u32(at + 8, s.bigEndian);
                valueAt = at + 12;
            } else if (among(vr, kShortVrs)) {
                length = u16(at + 6, s.bigEndian);
            } else {
                fail(at, std::string("element ") + tagName(group, elem) + " has an unknown VR " + printableVr(vr) +
                             (s.bigEndian ? " (explicit VR big endian)" : " (explicit VR little endian)"));
            }
        } else {
            length = u32(at + 4, s.bigEndian);
        }

        if (length == kUndefinedLength) {
            if (depth >= kMaxDicomSequenceDepth)
                fail(at, what + ": sequences nested deeper than " + std::to_string(kMaxDicomSequenceDepth));
            if (pixelData && (vr == "OB" || vr == "OW")) return {valueAt, fragments(valueAt, c, s)};
            if (vr == "SQ" || (!s.explicitVr && !pixelData)) return {valueAt, sequence(tagName(group, elem), valueAt, length, c, s, depth)};
            // PS3.5 6.2.2: a UN value of undefined length holds implicit VR little endian items.
            if (vr == "UN") return {valueAt, sequence(tagName(group, elem), valueAt, length, c, kImplicitLittle, depth)};
            fail(at, what + " has an undefined length (only sequences and encapsulated pixel data may)");
        }
        if (length % 2 != 0) fail(at, what + " has an odd length (" + std::to_string(length) + ")");
        if (length > c.end - valueAt)
            fail(at, what + " declares " + std::to_string(length) + " bytes, only " + std::to_string(c.end - valueAt) +
                         " remain in " + c.what);
        // A sequence of defined length; in implicit VR (and in UN, which GDCM turns back into
        // a sequence when its dictionary says so) a value that starts with an item tag is
        // walked as one, since GDCM parses it so.
        const bool startsWithItem = length >= 8 && !pixelData && u16(valueAt, s.bigEndian) == kItemGroup &&
                                    u16(valueAt + 2, s.bigEndian) == kItem;
        const bool startsWithLittleItem = length >= 8 && u16(valueAt, false) == kItemGroup && u16(valueAt + 2, false) == kItem;
        if (vr == "SQ" || (!s.explicitVr && startsWithItem) || (vr == "UN" && startsWithLittleItem)) {
            if (depth >= kMaxDicomSequenceDepth)
                fail(at, what + ": sequences nested deeper than " + std::to_string(kMaxDicomSequenceDepth));
            sequence(tagName(group, elem), valueAt, length, c, vr == "UN" ? kImplicitLittle : s, depth);
        }
        return {valueAt, valueAt + length};
    }

private:
    /// The items of the sequence `name` (its tag); `length` may be undefined.
    std::size_t sequence(const std::string& name, std::size_t valueAt, std::uint32_t length, Container outer, Syntax s,
                         int depth) const {
        const bool undefined = length == kUndefinedLength;
        const Container in = undefined ? outer : Container{valueAt + length, "its sequence"};
        std::size_t q = valueAt;
        for (;;) {
            if (!undefined && q == in.end) return q;
            if (in.end - q < 8) {
                if (undefined)
                    fail(q, "sequence " + name + " of undefined length has no sequence delimitation (FFFE,E0DD) before the end of " +
                                in.what);
                fail(q, std::to_string(in.end - q) + " byte(s) left in sequence " + name + ", too few for an item header");
            }
            const std::uint16_t group = u16(q, s.bigEndian), element = u16(q + 2, s.bigEndian);
            const std::uint32_t n = u32(q + 4, s.bigEndian);
            if (undefined && group == kItemGroup && element == kSequenceEnd) {
                if (n != 0) fail(q, "sequence delimitation (FFFE,E0DD) has length " + std::to_string(n) + " (must be 0)");
                return q + 8;
            }
            if (group != kItemGroup || element != kItem)
                fail(q, "sequence " + name + std::string(" holds ") + tagName(group, element) + " where an item (FFFE,E000) was expected");
            if (n == kUndefinedLength) {
                q = dataSet(q + 8, in, s, depth + 1, true);
                continue;
            }
            if (n % 2 != 0) fail(q, "item of sequence " + name + " has an odd length (" + std::to_string(n) + ")");
            if (n > in.end - (q + 8))
                fail(q, "item of sequence " + name + " declares " + std::to_string(n) + " bytes, only " +
                            std::to_string(in.end - (q + 8)) + " remain in " + in.what);
            dataSet(q + 8, Container{q + 8 + n, "its item"}, s, depth + 1, false);
            q += 8 + std::size_t(n);
        }
    }

    /// The fragments of encapsulated pixel data (PS3.5 A.4): items of defined length, then
    /// the sequence delimitation. Required even at the end of the file: without it GDCM
    /// makes up an empty fragment and asserts while decoding.
    std::size_t fragments(std::size_t valueAt, Container c, Syntax s) const {
        std::size_t q = valueAt;
        for (;;) {
            if (c.end - q < 8)
                fail(q, std::string("encapsulated pixel data have no sequence delimitation (FFFE,E0DD) before the end of ") + c.what);
            const std::uint16_t group = u16(q, s.bigEndian), element = u16(q + 2, s.bigEndian);
            const std::uint32_t n = u32(q + 4, s.bigEndian);
            if (group == kItemGroup && element == kSequenceEnd) {
                if (n != 0) fail(q, "sequence delimitation (FFFE,E0DD) has length " + std::to_string(n) + " (must be 0)");
                return q + 8;
            }
            if (group != kItemGroup || element != kItem)
                fail(q, std::string("encapsulated pixel data hold ") + tagName(group, element) + " where a fragment item (FFFE,E000) was expected");
            if (n == kUndefinedLength) fail(q, "a pixel data fragment has an undefined length");
            if (n % 2 != 0) fail(q, "a pixel data fragment has an odd length (" + std::to_string(n) + ")");
            if (n > c.end - (q + 8))
                fail(q, "a pixel data fragment declares " + std::to_string(n) + " bytes, only " + std::to_string(c.end - (q + 8)) +
                            " remain in " + c.what);
            // The first item is the offset table; a frame starts at a fragment that starts with SOI.
            if (jpeg_ && q != valueAt && n >= 2 && d_[q + 8] == 0xFF && d_[q + 9] == 0xD8) jpegHeader(q + 8, q + 8 + n);
            q += 8 + std::size_t(n);
        }
    }

    /// The header of the JPEG stream at [at, end) (ITU-T T.81 B.2-B.2.4: SOI, marker segments,
    /// SOS), as GDCM's JPEG codecs read it with the IJG library before decoding. GDCM asserts
    /// (and so aborts the process) when the library warns while reading a header, and on some
    /// values it does not handle: bytes other than fill (FF) before a marker (found by
    /// fuzz_dicom: garbage after a DQT segment), a stream that ends before its scan, a JFIF APP0
    /// of another major version, an Adobe APP14 colour transform the library does not know or
    /// GDCM does not handle (YCCK), a frame precision outside the standard's (whose refusal
    /// GDCM asserts on) and a component count other than 1, 3 or 4. The header is looked for
    /// in the frame's first fragment (encoders put it there).
    void jpegHeader(std::size_t at, std::size_t end) const {
        const auto marker = [](unsigned m) {
            char text[8];
            std::snprintf(text, sizeof text, "FF%02X", m);
            return std::string(text);
        };
        int components = 0, adobeTransform = -1;
        std::size_t q = at + 2;  // after SOI
        for (;;) {
            if (q >= end) fail(at, "a JPEG frame's fragment ends before its scan (no SOS marker in its header)");
            if (d_[q] != 0xFF) fail(q, "a JPEG frame's header holds bytes other than a marker between its segments");
            while (q < end && d_[q] == 0xFF) ++q;  // fill bytes
            if (q >= end) fail(at, "a JPEG frame's fragment ends before its scan (no SOS marker in its header)");
            const unsigned m = d_[q++];
            const std::size_t markerAt = q - 2;
            if (m == 0x00) fail(markerAt, "a JPEG frame's header holds bytes other than a marker between its segments");
            if (m == 0x01 || (m >= 0xD0 && m <= 0xD7)) continue;  // TEM, RSTn: no segment
            if (m == 0xD8 || m == 0xD9)
                fail(markerAt, std::string("a JPEG frame's header holds ") + (m == 0xD8 ? "a second SOI" : "EOI") + " before its scan");
            if (end - q < 2) fail(at, "a JPEG frame's fragment ends before its scan (no SOS marker in its header)");
            const std::size_t length = std::size_t(d_[q]) << 8 | d_[q + 1];
            if (length < 2 || length > end - q)
                fail(markerAt, "JPEG marker segment " + marker(m) + " declares " + std::to_string(length) + " bytes, " +
                                   std::to_string(end - q) + " remain in its fragment");
            const std::uint8_t* v = d_ + q + 2;  // the segment's parameters
            const std::size_t n = length - 2;
            if (m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC) {  // SOFn
                if (m > 0xC3)
                    fail(markerAt, "JPEG frame coded by " + marker(m) +
                                       " (hierarchical or arithmetic): octrace reads baseline, extended, progressive and lossless JPEG");
                if (n < 6) fail(markerAt, "JPEG frame header " + marker(m) + " of " + std::to_string(length) + " bytes");
                const int precision = v[0];
                if (m == 0xC3 ? precision < 2 || precision > 16 : precision != 8 && precision != 12)
                    fail(markerAt, "JPEG frame header " + marker(m) + " declares a sample precision of " + std::to_string(precision) +
                                       " bits (T.81: 8 or 12 for DCT coding, 2 to 16 for lossless)");
                components = v[5];
                if (components != 1 && components != 3 && components != 4)
                    fail(markerAt, "JPEG frame of " + std::to_string(components) + " components (1, 3 or 4 are read)");
            } else if (m == 0xE0 && n >= 14 && std::memcmp(v, "JFIF\0", 5) == 0 && v[5] != 1) {
                fail(markerAt, "JPEG frame with a JFIF segment of version " + std::to_string(v[5]) + "." + std::to_string(v[6]) +
                                   " (1.x is read)");
            } else if (m == 0xEE && n >= 12 && std::memcmp(v, "Adobe", 5) == 0) {
                adobeTransform = v[11];
            } else if (m == 0xDA) {
                // SOS: the header is complete. The colour transform as the library derives it.
                if (adobeTransform >= 0 && ((components == 3 && adobeTransform > 1) || (components == 4 && adobeTransform != 0)))
                    fail(markerAt, "JPEG frame of " + std::to_string(components) + " components with Adobe colour transform " +
                                       std::to_string(adobeTransform) + (components == 4 ? " (CMYK, transform 0, is read)" : " (0 or 1 is read)"));
                return;
            }
            q += length;
        }
    }

    const std::uint8_t* d_;
    std::size_t size_;
    const std::string& name_;
    bool jpeg_ = false;
};

// The transfer syntaxes whose pixel data GDCM decodes with the IJG JPEG library (its JPEG
// codecs): baseline, extended, the retired ones, progressive and lossless.
constexpr std::string_view kIjgJpegSyntaxes[] = {"1.2.840.10008.1.2.4.50", "1.2.840.10008.1.2.4.51", "1.2.840.10008.1.2.4.52",
                                                 "1.2.840.10008.1.2.4.53", "1.2.840.10008.1.2.4.55", "1.2.840.10008.1.2.4.57",
                                                 "1.2.840.10008.1.2.4.70"};

// The transfer syntaxes GDCM 3.0 knows whose data set is explicit VR little endian (natively
// or with encapsulated pixel data: JPEG, JPEG-LS, JPEG 2000, JPIP, RLE, MPEG-2, H.264). GDCM
// throws on any other UID and retries in its compatibility mode, where it may abort.
constexpr std::string_view kExplicitLittleSyntaxes[] = {
    "1.2.840.10008.1.2.1",      "1.2.840.10008.1.2.4.50",  "1.2.840.10008.1.2.4.51",  "1.2.840.10008.1.2.4.52",
    "1.2.840.10008.1.2.4.53",   "1.2.840.10008.1.2.4.55",  "1.2.840.10008.1.2.4.57",  "1.2.840.10008.1.2.4.70",
    "1.2.840.10008.1.2.4.80",   "1.2.840.10008.1.2.4.81",  "1.2.840.10008.1.2.4.90",  "1.2.840.10008.1.2.4.91",
    "1.2.840.10008.1.2.4.92",   "1.2.840.10008.1.2.4.93",  "1.2.840.10008.1.2.4.94",  "1.2.840.10008.1.2.4.100",
    "1.2.840.10008.1.2.4.101",  "1.2.840.10008.1.2.4.102", "1.2.840.10008.1.2.4.103", "1.2.840.10008.1.2.5"};

// The data set's encoding from the meta group's TransferSyntaxUID.
Syntax dataSetSyntax(const Walker& w, std::size_t at, const std::string& uid) {
    if (uid == "1.2.840.10008.1.2") return kImplicitLittle;
    if (uid == "1.2.840.10008.1.2.2") return kExplicitBig;
    if (among(uid, kExplicitLittleSyntaxes)) return kExplicitLittle;
    // Deflated: the data set is a zlib stream; refused rather than inflated only to be checked.
    if (uid == "1.2.840.10008.1.2.1.99") w.fail(at, "transfer syntax " + uid + " (deflated) is not supported");
    w.fail(at, "transfer syntax '" + uid + "' is not one octrace reads");
}

std::string uidText(std::string_view value) {
    while (!value.empty() && (value.back() == '\0' || value.back() == ' ')) value.remove_suffix(1);
    std::string out;
    for (char c : value) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return out;
}

}  // namespace

bool validateDicomBytes(const std::uint8_t* data, std::size_t size, const std::string& name, std::string& whyNot) {
    const bool preamble = size >= 132 && std::memcmp(data + 128, "DICM", 4) == 0;
    std::size_t p = preamble ? 132 : 0;
    Walker w(data, size, name);
    const Container file{size, "the file"};
    if (!preamble) {
        // No preamble: GDCM also reads a file that starts with the meta group, or a bare little
        // endian data set (ACR-NEMA style) beginning with the identifying group (0008).
        const std::uint16_t first = size >= 8 ? w.u16(0, false) : 0xFFFF;
        if (first != 0x0002 && first != 0x0008) {
            whyNot = "not a DICOM file (no 'DICM' at byte 128, no DICOM element at its start)";
            return false;
        }
    }
    Syntax syntax = kImplicitLittle;
    if (size - p >= 8 && w.u16(p, false) == 0x0002) {
        // The file meta group, explicit VR little endian, opened by its group length (GDCM
        // refuses a group without it and falls back to a mode that may abort).
        if (w.u16(p + 2, false) != 0x0000 || w.bytes(p + 4, 2) != "UL" || w.u16(p + 6, false) != 4)
            w.fail(p, "the file meta group does not start with its group length (0002,0000) UL");
        std::string uid;
        bool haveUid = false;
        while (size - p >= 8 && w.u16(p, false) == 0x0002) {
            const std::string_view vr = w.bytes(p + 4, 2);
            if (vr == "SQ" || vr == "UN")
                w.fail(p, std::string("element ") + tagName(0x0002, w.u16(p + 2, false)) + " of the file meta group has VR " + std::string(vr));
            const Parsed e = w.element(p, file, kExplicitLittle, 0);
            if (w.u16(p + 2, false) == 0x0010) {
                uid = uidText(w.bytes(e.valueAt, e.next - e.valueAt));
                haveUid = true;
            }
            p = e.next;
        }
        if (!haveUid) w.fail(p, "the file meta group has no TransferSyntaxUID (0002,0010)");
        syntax = dataSetSyntax(w, p, uid);
        w.setJpegFragments(among(uid, kIjgJpegSyntaxes));
        // GDCM's meta reader expects a next element (it asserts on the end of the file there).
        if (p == size) w.fail(p, "the file ends after its file meta group (no data set)");
    } else if (preamble) {
        w.fail(p, "no file meta group (0002,xxxx) after 'DICM'");
    } else if (isVr(w.bytes(4, 2))) {
        syntax = kExplicitLittle;  // a bare data set: explicit VR when a VR follows the first tag, as GDCM decides
    }
    w.dataSet(p, file, syntax, 0, false);
    return true;
}

bool validateDicomFile(const std::string& file, std::string& whyNot) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw InputError(file + ": cannot be opened");
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw InputError(file + ": cannot be opened (not a regular file)");
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    if (size == 0) {
        ::close(fd);
        whyNot = "not a DICOM file (0 bytes)";
        return false;
    }
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (map == MAP_FAILED) throw InputError(file + ": cannot be memory-mapped");
    struct Unmap {
        void* p;
        std::size_t n;
        ~Unmap() { ::munmap(p, n); }
    } unmap{map, size};
    return validateDicomBytes(static_cast<const std::uint8_t*>(map), size, file, whyNot);
}

}  // namespace octrace::io::detail

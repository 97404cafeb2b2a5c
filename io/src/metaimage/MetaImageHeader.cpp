#include "metaimage/MetaImageHeader.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace octrace::io::detail {
namespace {

// A header is a few hundred bytes; anything longer before ElementDataFile is not one.
constexpr std::size_t kMaxHeaderBytes = 65536;

// The keys octrace interprets, as MetaIO spells them.
constexpr const char* kMetaImageKeys[] = {
    "ObjectType", "NDims", "DimSize", "ElementSpacing", "ElementSize", "Offset", "Position", "Origin",
    "TransformMatrix", "Rotation", "Orientation", "ElementType", "ElementNumberOfChannels", "CompressedData",
    "CompressedDataSize", "BinaryDataByteOrderMSB", "ElementByteOrderMSB", "BinaryData", "HeaderSize",
    "AnatomicalOrientation", "ElementDataFile"};

// Deflate expands at most 1032:1 (zlib's technical details).
constexpr std::uint64_t kMaxDeflateRatio = 1032;

// Element types of MetaIO (metaTypes.h) and their sizes.
std::size_t elementSize(const std::string& t) {
    if (t == "MET_CHAR" || t == "MET_UCHAR") return 1;
    if (t == "MET_SHORT" || t == "MET_USHORT") return 2;
    if (t == "MET_INT" || t == "MET_UINT" || t == "MET_FLOAT") return 4;
    if (t == "MET_LONG_LONG" || t == "MET_ULONG_LONG" || t == "MET_DOUBLE") return 8;
    return 0;
}

struct Parser {
    const std::string& path;
    [[noreturn]] void fail(const std::string& what) const { throw FileError(path + ": MetaImage header: " + what); }

    static std::string howMany(std::size_t count, const char* kind) {
        return count == 1 ? std::string("a ") + kind + "number" : std::to_string(count) + " " + kind + "numbers";
    }
    std::vector<double> numbers(const std::string& key, const std::string& value, std::size_t count) const {
        std::istringstream in(value);
        std::vector<double> v;
        for (std::string item; in >> item;) {
            char* end = nullptr;
            errno = 0;
            const double x = std::strtod(item.c_str(), &end);
            if (*end != '\0' || errno == ERANGE || !std::isfinite(x))
                fail(key + " '" + quoteBytes(value) + "' is not " + howMany(count, "finite "));
            v.push_back(x);
        }
        if (v.size() != count) fail(key + " '" + quoteBytes(value) + "' is not " + howMany(count, ""));
        return v;
    }
    bool boolean(const std::string& key, const std::string& value) const {
        const std::string v = lower(value);
        if (v == "true" || v == "1") return true;
        if (v == "false" || v == "0") return false;
        fail(key + " '" + quoteBytes(value) + "' is neither True nor False");
    }
};

}  // namespace

MetaImageHeader MetaImageHeader::parseText(const std::string& path, const std::string& text) {
    const Parser p{path};
    MetaImageHeader h;
    h.path = path;
    bool sawNDims = false, sawDims = false, sawKey = false, sawSpacing = false;
    std::size_t pos = 0;
    for (;;) {
        if (pos >= text.size()) {
            if (!sawKey) throw FormatNotSupported(path + ": not a MetaImage header (no 'Key = Value' line)");
            p.fail(text.size() >= kMaxHeaderBytes ? "no ElementDataFile line in the first 64 KiB"
                                                  : "no ElementDataFile line (it must end the header)");
        }
        std::size_t end = text.find('\n', pos);
        const bool lastLine = end == std::string::npos;
        if (lastLine) end = text.size();
        std::string line = text.substr(pos, end - pos);
        pos = end + 1;
        // Plain text only: a control character other than a tab (and the CR of a CRLF line end)
        // is where MetaIO and octrace would split the line differently. MetaIO ends a key at a
        // CR and does not skip a CR before a value, so 'ElementDataFile = <CR>LOCAL' names a
        // data file to VTK and LOCAL to octrace (fuzz_metaimage found it).
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto control = std::find_if(line.begin(), line.end(), [](char c) {
            const auto u = static_cast<unsigned char>(c);
            return (u < 0x20 && c != '\t') || u == 0x7f;
        });
        if (control != line.end()) {
            if (!sawKey) throw FormatNotSupported(path + ": not a MetaImage header (binary data)");
            char what[32];
            std::snprintf(what, sizeof what, "control character 0x%02X", unsigned(static_cast<unsigned char>(*control)));
            p.fail(std::string(*control == '\0' ? "NUL byte" : what) + " in the header before ElementDataFile (line '" +
                   quoteBytes(trim(line).substr(0, 60)) + "'): a MetaImage header is plain text");
        }
        line = trim(line);
        if (line.empty()) continue;
        // MetaIO ends a key at '=' or ':', whichever comes first.
        const std::size_t eq = line.find_first_of("=:");
        if (eq == std::string::npos) {
            if (!sawKey) throw FormatNotSupported(path + ": not a MetaImage header (first line '" + quoteBytes(line.substr(0, 40)) + "')");
            p.fail("line '" + quoteBytes(line.substr(0, 60)) + "' is not 'Key = Value'");
        }
        const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
        const std::string k = lower(key);
        sawKey = true;
        // VTK's MetaIO matches keys case-sensitively: a key octrace would read in another case
        // is one VTK skips, and the two would see different headers (fuzz_metaimage found a
        // header whose 'ElementDataFIle = LOCAL' octrace took for the end and VTK did not).
        for (const char* canonical : kMetaImageKeys)
            if (k == lower(canonical) && key != canonical)
                p.fail("key '" + quoteBytes(key) + "' must be spelled '" + canonical + "' (MetaImage keys are case-sensitive)");
        if (k == "objecttype") {
            if (lower(value) != "image") p.fail("ObjectType '" + quoteBytes(value) + "' is not Image");
        } else if (k == "ndims") {
            if (value != "3") p.fail("NDims " + quoteBytes(value) + ": octrace reads 3-D images only");
            sawNDims = true;
        } else if (k == "dimsize") {
            const std::vector<double> d = p.numbers(key, value, 3);
            for (int a = 0; a < 3; ++a) {
                if (d[std::size_t(a)] < 1 || d[std::size_t(a)] > double(kMaxAxisPoints) || d[std::size_t(a)] != std::floor(d[std::size_t(a)]))
                    p.fail("DimSize '" + quoteBytes(value) + "': each must be an integer in 1.." + std::to_string(kMaxAxisPoints));
                h.dims[a] = int(d[std::size_t(a)]);
            }
            sawDims = true;
        } else if (k == "elementspacing" || (k == "elementsize" && !sawSpacing)) {
            sawSpacing = sawSpacing || k == "elementspacing";
            const std::vector<double> s = p.numbers(key, value, 3);
            for (int a = 0; a < 3; ++a) h.spacing[a] = s[std::size_t(a)];
            if (!(h.spacing.x > 0.0 && h.spacing.y > 0.0 && h.spacing.z > 0.0)) p.fail(key + " '" + value + "' must be positive");
        } else if (k == "offset" || k == "position" || k == "origin") {
            const std::vector<double> o = p.numbers(key, value, 3);
            h.origin = dvec3(o[0], o[1], o[2]);
        } else if (k == "transformmatrix" || k == "rotation" || k == "orientation") {
            const std::vector<double> m = p.numbers(key, value, 9);
            // As ITK's MetaImageIO reads it: values 3a..3a+2 are the world direction of axis a.
            for (int a = 0; a < 3; ++a)
                h.direction[a] = dvec3(m[std::size_t(3 * a)], m[std::size_t(3 * a + 1)], m[std::size_t(3 * a + 2)]);
            h.hasDirection = true;
        } else if (k == "elementtype") {
            h.elementType = value;
            h.typeSize = elementSize(value);
            if (h.typeSize == 0) p.fail("ElementType '" + quoteBytes(value) + "' is not one octrace reads (MET_CHAR .. MET_DOUBLE)");
        } else if (k == "elementnumberofchannels") {
            if (value != "1") p.fail("ElementNumberOfChannels " + quoteBytes(value) + ": a volume needs one value per sample");
        } else if (k == "compresseddata") {
            h.compressed = p.boolean(key, value);
        } else if (k == "compresseddatasize") {
            // MetaIO reads it as a number; 0 means unknown, as when it is absent.
            const double n = p.numbers(key, value, 1)[0];
            if (n < 0 || n != std::floor(n) || n > 9e18) p.fail("CompressedDataSize '" + quoteBytes(value) + "' is not a byte count");
            h.compressedSize = std::uint64_t(n);
        } else if (k == "binarydatabyteordermsb" || k == "elementbyteordermsb") {
            h.bigEndian = p.boolean(key, value);
        } else if (k == "binarydata") {
            if (!p.boolean(key, value)) p.fail("BinaryData False (ASCII samples) is not supported");
        } else if (k == "headersize") {
            char* stop = nullptr;
            const long long n = std::strtoll(value.c_str(), &stop, 10);
            if (*stop != '\0' || value.empty() || n < 0)
                p.fail("HeaderSize '" + quoteBytes(value) + "' is not supported (a byte count, not -1)");
            h.dataOffset = std::uint64_t(n);
        } else if (k == "anatomicalorientation") {
            h.anatomicalOrientation = value;
        } else if (k == "elementdatafile") {
            if (!sawNDims || !sawDims || h.typeSize == 0) p.fail("NDims, DimSize and ElementType must come before ElementDataFile");
            if (value.empty()) p.fail("ElementDataFile is empty");
            if (lower(value) == "list" || value.find('%') != std::string::npos || value.find(' ') != std::string::npos)
                p.fail("ElementDataFile '" + quoteBytes(value) + "': lists and patterns of slice files are not supported");
            if (value == "LOCAL") {
                if (lastLine) p.fail("no data after ElementDataFile = LOCAL");
                h.dataFile = "LOCAL";
                h.dataOffset = pos;  // the samples follow the header line
            } else {
                std::filesystem::path f(value);
                if (f.is_relative()) f = std::filesystem::path(path).parent_path() / f;
                h.dataFile = f.lexically_normal().string();
            }
            return h;
        }
        // Other keys (Comment, CenterOfRotation, ElementMin, ...) do not change the samples.
    }
}

MetaImageHeader MetaImageHeader::parse(const std::string& path) {
    requireReadableFile(path);
    const std::string head = readPrefix(path, kMaxHeaderBytes);
    if (head.empty()) throw FileError(path + ": file is empty (0 bytes)");
    return parseText(path, head);
}

std::string MetaImageHeader::shapeText() const {
    return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) + " " + elementType;
}

void MetaImageHeader::checkData() const {
    const std::string& file = sampleFile();
    if (file != path) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) throw FileError(path + ": data file '" + file + "' not found");
        requireReadableFile(file);
    }
    const std::uintmax_t size = fileSize(file);
    const std::uintmax_t start = std::min<std::uintmax_t>(dataOffset, size);
    const std::uint64_t need = byteCount();
    if (compressed) {
        if (size <= start) throw FileError(path + ": no compressed data in '" + file + "'");
        if (compressedSize > size - start)
            throw FileError(path + ": CompressedDataSize " + std::to_string(compressedSize) + " but '" + file + "' holds " +
                            std::to_string(size - start) + " bytes from byte " + std::to_string(start));
        const std::uint64_t have = compressedBytes(size);
        if (need / kMaxDeflateRatio > have)
            throw FileError(path + ": compressed data truncated: " + shapeText() + " need " + std::to_string(need) + " bytes, " +
                            std::to_string(have) + " compressed bytes inflate to at most " + std::to_string(have * kMaxDeflateRatio) +
                            " (deflate expands at most 1032:1)");
        return;
    }
    if (size - start < need)
        throw FileError(path + ": data truncated: " + shapeText() + " need " + std::to_string(need) + " bytes, '" + file +
                        "' holds " + std::to_string(size - start) + " from byte " + std::to_string(start));
}

namespace {

// `n` samples of type T from `bytes`, byte order reversed when `swap`.
template <class T>
void toFloats(const unsigned char* bytes, std::size_t n, bool swap, float* out) {
    unsigned char b[sizeof(T)];
    for (std::size_t i = 0; i < n; ++i, bytes += sizeof(T)) {
        std::memcpy(b, bytes, sizeof(T));
        if (swap) std::reverse(b, b + sizeof(T));
        T v;
        std::memcpy(&v, b, sizeof(T));
        out[i] = static_cast<float>(v);
    }
}

// Ends a zlib stream however the inflation is left.
struct Inflater {
    z_stream z{};
    Inflater() {
        if (inflateInit2(&z, 15 + 32) != Z_OK) throw FileError("zlib: cannot start inflating");  // zlib or gzip header
    }
    ~Inflater() { inflateEnd(&z); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;
};

// Inflates `total` bytes of `in` (zlib or gzip) into exactly `need` bytes.
std::vector<unsigned char> inflateExactly(std::ifstream& in, std::uint64_t total, std::uint64_t need, const std::string& path,
                                          const std::string& file, const std::string& shape) {
    std::uint64_t left = total;
    std::vector<unsigned char> bytes(need);
    std::vector<unsigned char> chunk(std::size_t(1) << 20);
    Inflater inf;
    z_stream& z = inf.z;
    std::uint64_t produced = 0;
    int rc = Z_OK;
    while (rc != Z_STREAM_END) {
        if (z.avail_in == 0) {
            if (left == 0) break;
            const std::size_t n = std::size_t(std::min<std::uint64_t>(left, chunk.size()));
            in.read(reinterpret_cast<char*>(chunk.data()), std::streamsize(n));
            if (std::size_t(in.gcount()) != n) throw FileError(path + ": cannot read the compressed data of '" + file + "'");
            left -= n;
            z.next_in = chunk.data();
            z.avail_in = uInt(n);
        }
        // Once every sample is in, one byte more tells a stream that holds more from one
        // that only has its end (and checksum) to go.
        unsigned char extra = 0;
        const bool full = produced == need;
        z.next_out = full ? &extra : bytes.data() + produced;
        z.avail_out = full ? 1u : uInt(std::min<std::uint64_t>(need - produced, std::uint64_t(1) << 30));
        const uInt before = z.avail_out;
        rc = inflate(&z, Z_NO_FLUSH);
        if (rc == Z_NEED_DICT || rc == Z_DATA_ERROR || rc == Z_MEM_ERROR || rc == Z_STREAM_ERROR)
            throw FileError(path + ": compressed data corrupt after " + std::to_string(produced) + " of " + std::to_string(need) +
                            " bytes (" + shape + "): zlib: " + (z.msg ? z.msg : rc == Z_NEED_DICT ? "needs a preset dictionary" : "error"));
        if (full && z.avail_out == 0)
            throw FileError(path + ": compressed data inflate to more than the " + std::to_string(need) + " bytes of " + shape);
        if (!full) produced += before - z.avail_out;
    }
    if (rc == Z_STREAM_END && produced < need)
        throw FileError(path + ": compressed data truncated: " + shape + " need " + std::to_string(need) +
                        " bytes, the zlib stream ends after " + std::to_string(produced));
    if (rc != Z_STREAM_END)
        throw FileError(path + ": compressed data truncated: " + shape + " need " + std::to_string(need) + " bytes, the " +
                        std::to_string(total - left) + " compressed bytes stop after " + std::to_string(produced) +
                        (produced == need ? " without the end of the zlib stream" : ""));
    return bytes;
}

}  // namespace

std::vector<float> MetaImageHeader::readSamples() const {
    const std::string& file = sampleFile();
    const std::uint64_t need = byteCount();
    const std::string shape = shapeText();
    std::ifstream in(file, std::ios::binary);
    in.seekg(std::streamoff(dataOffset));
    if (!in) throw FileError(path + ": cannot read the data of '" + file + "'");
    std::vector<unsigned char> bytes;
    if (compressed) {
        bytes = inflateExactly(in, compressedBytes(fileSize(file)), need, path, file, shape);
    } else {
        bytes.resize(need);
        in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(need));
        if (std::uint64_t(in.gcount()) != need)
            throw FileError(path + ": cannot read the " + std::to_string(need) + " bytes of " + shape + " from '" + file + "'");
    }

    std::vector<float> values(sampleCount());
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    const unsigned char* b = bytes.data();
    float* out = values.data();
    const std::size_t n = values.size();
    if (elementType == "MET_CHAR") toFloats<std::int8_t>(b, n, swap, out);
    else if (elementType == "MET_UCHAR") toFloats<std::uint8_t>(b, n, swap, out);
    else if (elementType == "MET_SHORT") toFloats<std::int16_t>(b, n, swap, out);
    else if (elementType == "MET_USHORT") toFloats<std::uint16_t>(b, n, swap, out);
    else if (elementType == "MET_INT") toFloats<std::int32_t>(b, n, swap, out);
    else if (elementType == "MET_UINT") toFloats<std::uint32_t>(b, n, swap, out);
    else if (elementType == "MET_FLOAT") toFloats<float>(b, n, swap, out);
    else if (elementType == "MET_LONG_LONG") toFloats<std::int64_t>(b, n, swap, out);
    else if (elementType == "MET_ULONG_LONG") toFloats<std::uint64_t>(b, n, swap, out);
    else if (elementType == "MET_DOUBLE") toFloats<double>(b, n, swap, out);
    else throw FileError(path + ": ElementType '" + elementType + "' cannot be decoded");
    return values;
}

}  // namespace octrace::io::detail

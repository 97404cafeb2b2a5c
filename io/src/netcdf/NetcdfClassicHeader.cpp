#include "netcdf/NetcdfClassicHeader.h"

#include "input/InputFile.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <vector>

namespace octrace::io::detail {
namespace {

// Big-endian fields of the classic format; see the NetCDF "File Format Specification".
// Every skip is checked against the file's size: a name or attribute length of 2^63 or more
// would otherwise seek backwards (std::streamoff is signed) and walk the same bytes forever.
class HeaderStream {
public:
    HeaderStream(std::istream& in, std::uint64_t size, const std::string& path) : path_(path), in_(in), size_(size) {}

    [[noreturn]] void fail(const std::string& what) const { throw FileError(path_ + ": NetCDF header " + what); }

    std::uint64_t u32() { return bytes(4); }
    std::uint64_t u64() { return bytes(8); }
    void skip(std::uint64_t n) {
        if (n > size_ - pos_) fail("is truncated");
        in_.seekg(std::streamoff(n), std::ios::cur);
        if (!in_) fail("is truncated");
        pos_ += n;
    }

private:
    std::uint64_t bytes(int n) {
        unsigned char b[8];
        if (std::uint64_t(n) > size_ - pos_ || !in_.read(reinterpret_cast<char*>(b), n)) fail("is truncated");
        pos_ += std::uint64_t(n);
        std::uint64_t v = 0;
        for (int i = 0; i < n; ++i) v = (v << 8) | b[i];
        return v;
    }
    std::string path_;
    std::istream& in_;
    std::uint64_t size_, pos_ = 0;
};

constexpr std::uint64_t kDimensionTag = 10, kVariableTag = 11, kAttributeTag = 12;

std::uint64_t typeSize(std::uint64_t type) {
    switch (type) {
        case 1: case 2: case 7: return 1;  // byte, char, ubyte
        case 3: case 8: return 2;          // short, ushort
        case 4: case 5: case 9: return 4;  // int, float, uint
        case 6: case 10: case 11: return 8;  // double, int64, uint64
        default: return 0;
    }
}

// Sizes a header announces can overflow 64 bits; saturated, they still exceed any real file,
// so such a file is reported as truncated instead of wrapping around to a small size.
constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
std::uint64_t mulSat(std::uint64_t a, std::uint64_t b) { return b != 0 && a > kMax / b ? kMax : a * b; }
std::uint64_t addSat(std::uint64_t a, std::uint64_t b) { return a > kMax - b ? kMax : a + b; }
std::uint64_t pad4(std::uint64_t n) { return n > kMax - 3 ? kMax : (n + 3) / 4 * 4; }

}  // namespace

std::uint64_t classicDataEnd(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return classicDataEnd(in, fileSize(path), path);
}

std::uint64_t classicDataEnd(std::istream& in, std::uint64_t size, const std::string& path) {
    HeaderStream h(in, size, path);
    std::uint64_t magic = h.u32();
    int version = int(magic & 0xff);
    bool cdf5 = version == 5;
    auto count = [&] { return cdf5 ? h.u64() : h.u32(); };  // nelems, dim lengths, dim ids, vsize
    auto name = [&] { h.skip(pad4(count())); };
    auto attributes = [&] {
        std::uint64_t tag = h.u32(), n = count();
        if (tag == 0 && n == 0) return;
        if (tag != kAttributeTag) h.fail("has a malformed attribute list");
        for (std::uint64_t a = 0; a < n; ++a) {
            name();
            std::uint64_t size = typeSize(h.u32());
            if (size == 0) h.fail("has an attribute of unknown type");
            h.skip(pad4(mulSat(count(), size)));
        }
    };

    std::uint64_t numRecords = count();
    bool streaming = numRecords == (cdf5 ? ~0ull : 0xffffffffull);

    std::vector<std::uint64_t> dimLength;
    std::uint64_t tag = h.u32(), n = count();
    if (!(tag == 0 && n == 0) && tag != kDimensionTag) h.fail("has a malformed dimension list");
    for (std::uint64_t d = 0; d < n && tag == kDimensionTag; ++d) {
        name();
        dimLength.push_back(count());
    }
    attributes();  // global

    struct Var {
        std::uint64_t begin, bytes;  // bytes: one record's slab for record variables
        bool record;
    };
    std::vector<Var> vars;
    tag = h.u32();
    n = count();
    if (!(tag == 0 && n == 0) && tag != kVariableTag) h.fail("has a malformed variable list");
    for (std::uint64_t v = 0; v < n && tag == kVariableTag; ++v) {
        name();
        std::uint64_t rank = count(), elements = 1;
        bool record = false;
        for (std::uint64_t r = 0; r < rank; ++r) {
            std::uint64_t id = count();
            if (id >= dimLength.size()) h.fail("refers to a dimension that does not exist");
            if (dimLength[id] == 0 && r == 0) record = true;
            else elements = mulSat(elements, dimLength[id]);
        }
        attributes();
        std::uint64_t size = typeSize(h.u32());
        if (size == 0) h.fail("has a variable of unknown type");
        count();  // vsize: may be clamped for huge variables, so recomputed from the dimensions
        std::uint64_t begin = version == 1 ? h.u32() : h.u64();
        vars.push_back({begin, mulSat(elements, size), record});
    }

    std::uint64_t recordSize = 0;
    std::size_t recordVars = 0;
    for (const auto& v : vars)
        if (v.record) { recordSize = addSat(recordSize, pad4(v.bytes)); ++recordVars; }
    if (recordVars == 1) recordSize = std::find_if(vars.begin(), vars.end(), [](const Var& v) { return v.record; })->bytes;

    std::uint64_t end = 0;
    for (const auto& v : vars) {
        if (!v.record) end = std::max(end, addSat(v.begin, v.bytes));
        else if (!streaming && numRecords > 0)
            end = std::max(end, addSat(addSat(v.begin, mulSat(numRecords - 1, recordSize)), v.bytes));
    }
    return end;
}

}  // namespace octrace::io::detail

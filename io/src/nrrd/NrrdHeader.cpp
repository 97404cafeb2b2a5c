#include "nrrd/NrrdHeader.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace octrace::io::detail {
namespace {

constexpr std::size_t kMaxHeaderBytes = 4u << 20;  // as vtkNrrdReader
constexpr double kMaxSamples = 4294967296.0;      // 16 GiB of float samples

struct TypeName {
    const char* alias;
    const char* type;
    std::size_t size;
};
const TypeName kTypes[] = {
    {"signed char", "int8", 1}, {"int8", "int8", 1}, {"int8_t", "int8", 1},
    {"uchar", "uint8", 1}, {"unsigned char", "uint8", 1}, {"uint8", "uint8", 1}, {"uint8_t", "uint8", 1},
    {"short", "int16", 2}, {"short int", "int16", 2}, {"signed short", "int16", 2},
    {"signed short int", "int16", 2}, {"int16", "int16", 2}, {"int16_t", "int16", 2},
    {"ushort", "uint16", 2}, {"unsigned short", "uint16", 2}, {"unsigned short int", "uint16", 2},
    {"uint16", "uint16", 2}, {"uint16_t", "uint16", 2},
    {"int", "int32", 4}, {"signed int", "int32", 4}, {"int32", "int32", 4}, {"int32_t", "int32", 4},
    {"uint", "uint32", 4}, {"unsigned int", "uint32", 4}, {"uint32", "uint32", 4}, {"uint32_t", "uint32", 4},
    {"longlong", "int64", 8}, {"long long", "int64", 8}, {"long long int", "int64", 8},
    {"signed long long", "int64", 8}, {"signed long long int", "int64", 8}, {"int64", "int64", 8},
    {"int64_t", "int64", 8},
    {"ulonglong", "uint64", 8}, {"unsigned long long", "uint64", 8}, {"unsigned long long int", "uint64", 8},
    {"uint64", "uint64", 8}, {"uint64_t", "uint64", 8},
    {"float", "float", 4}, {"double", "double", 8},
};

std::vector<std::string> words(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

double toDouble(const std::string& s, bool& ok) {
    char* end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    ok = !s.empty() && *end == '\0';
    return v;
}

// A pattern for snprintf must hold exactly one integer conversion (e.g. "slice.%03d"), with
// a width of at most 16: vtkNrrdReader formats the names into a buffer only 20 bytes longer
// than the pattern (a wider number would be cut, and VTK would open another file than the
// one checked here), and glibc would pad a width of 10^9 for seconds.
constexpr int kMaxPatternWidth = 16;

bool safeIntegerPattern(const std::string& f) {
    int conversions = 0;
    for (std::size_t i = 0; i < f.size(); ++i) {
        if (f[i] != '%') continue;
        if (i + 1 < f.size() && f[i + 1] == '%') { ++i; continue; }
        std::size_t j = i + 1;
        while (j < f.size() && std::string("-+ #0").find(f[j]) != std::string::npos) ++j;  // flags
        int width = 0;
        for (; j < f.size() && f[j] >= '0' && f[j] <= '9'; ++j)
            if ((width = width * 10 + (f[j] - '0')) > kMaxPatternWidth) return false;
        if (j >= f.size() || std::string("diuxXo").find(f[j]) == std::string::npos) return false;
        ++conversions;
        i = j;
    }
    return conversions == 1;
}

// A whole decimal number within +-limit (the numbers of a data file pattern).
bool boundedInteger(const std::string& s, long long limit, long long& out) {
    char* end = nullptr;
    errno = 0;
    out = std::strtoll(s.c_str(), &end, 10);
    return !s.empty() && *end == '\0' && errno == 0 && out >= -limit && out <= limit;
}

class Parser {
public:
    explicit Parser(NrrdHeader& h) : h_(h) {}

    [[noreturn]] void fail(const std::string& what) const { throw FileError(h_.path + ": " + what); }

    // "(a,b,c)" with optional spaces.
    dvec3 vector3(const std::string& field, std::string s) const {
        s = trim(s);
        if (s.size() < 2 || s.front() != '(' || s.back() != ')')
            fail("'" + field + "': expected a vector like (1,0,0), got '" + s + "'");
        std::stringstream in(s.substr(1, s.size() - 2));
        std::vector<double> v;
        for (std::string item; std::getline(in, item, ',');) {
            bool ok = false;
            double d = toDouble(trim(item), ok);
            if (!ok || !std::isfinite(d)) fail("'" + field + "': '" + trim(item) + "' is not a finite number");
            v.push_back(d);
        }
        if (v.size() != 3)
            fail("'" + field + "': expected 3 components per vector (3-D space), got " + std::to_string(v.size()));
        return {v[0], v[1], v[2]};
    }

    // Splits "(a,b,c) (d,e,f) (g,h,i)" (spaces inside parentheses allowed) into vectors.
    std::vector<std::string> vectorItems(const std::string& s) const {
        std::vector<std::string> out;
        std::string cur;
        int depth = 0;
        for (char c : s) {
            if (c == '(') ++depth;
            if (c == ')') --depth;
            if (std::isspace(static_cast<unsigned char>(c)) && depth == 0) {
                if (!cur.empty()) out.push_back(cur);
                cur.clear();
            } else {
                cur += c;
            }
        }
        if (!cur.empty()) out.push_back(cur);
        return out;
    }

    // A NRRD header is text. vtkNrrdReader handles it as a C string cut at the first NUL byte:
    // with one in any line, even a comment, its header loop never ends (see NrrdReader.cpp)
    // and it takes the whole file for the header, so it would read data from the wrong offset.
    void requireText(const std::string& line, int lineNo) const {
        if (line.find('\0') != std::string::npos)
            fail("header line " + std::to_string(lineNo) + " holds a NUL byte: a NRRD header is text");
    }

    void needDimension(const std::string& field) const {
        if (h_.dimension == 0) fail("'" + field + "' appears before 'dimension'");
    }

    void field(const std::string& name, const std::string& value) {
        if (name == "dimension") {
            h_.dimension = std::atoi(value.c_str());
            if (h_.dimension != 3)
                fail("expected a 3-D scalar volume, header says 'dimension: " + value + "'");
        } else if (name == "type") {
            std::string t = lower(value);
            for (const auto& e : kTypes)
                if (t == e.alias) { h_.type = e.type; h_.typeSize = e.size; }
            if (h_.type.empty()) fail("sample type '" + value + "' is not supported");
        } else if (name == "encoding") {
            std::string e = lower(value);
            if (e == "raw") h_.encoding = "raw";
            else if (e == "gzip" || e == "gz") h_.encoding = "gzip";
            else if (e == "ascii" || e == "txt" || e == "text") h_.encoding = "ascii";
            else fail("encoding '" + value + "' is not supported (raw, gzip and ascii are)");
        } else if (name == "endian") {
            h_.endian = lower(value);
            if (h_.endian != "little" && h_.endian != "big") fail("endian must be 'little' or 'big', is '" + value + "'");
        } else if (name == "sizes") {
            needDimension(name);
            auto w = words(value);
            if (int(w.size()) != h_.dimension)
                fail("'sizes' has " + std::to_string(w.size()) + " values, expected " + std::to_string(h_.dimension));
            for (int a = 0; a < 3; ++a) {
                char* end = nullptr;
                errno = 0;
                long long n = std::strtoll(w[std::size_t(a)].c_str(), &end, 10);
                if (*end != '\0' || n <= 0)
                    fail("size of axis " + std::to_string(a) + " must be a positive integer, is '" + w[std::size_t(a)] + "'");
                if (errno == ERANGE || std::uint64_t(n) > kMaxAxisPoints)
                    fail("size of axis " + std::to_string(a) + " is " + w[std::size_t(a)] + ", more than the " +
                         std::to_string(kMaxAxisPoints) + " (2^24) octrace reads along one axis");
                h_.sizes[a] = int(n);
            }
        } else if (name == "spacings") {
            needDimension(name);
            auto w = words(value);
            if (int(w.size()) != h_.dimension)
                fail("'spacings' has " + std::to_string(w.size()) + " values, expected " + std::to_string(h_.dimension));
            for (int a = 0; a < 3; ++a) {
                bool ok = false;
                double s = toDouble(w[std::size_t(a)], ok);
                if (ok && std::isnan(s)) {
                    log::warning(h_.path + ": spacing of axis " + std::to_string(a) + " is unknown (nan), using 1");
                    s = 1.0;
                }
                if (!ok || !std::isfinite(s) || s <= 0.0)
                    fail("spacing along axis " + std::to_string(a) + " must be positive, is '" + w[std::size_t(a)] + "'");
                h_.spacings[a] = s;
            }
            h_.hasSpacings = true;
        } else if (name == "space directions") {
            auto items = vectorItems(value);
            if (items.size() != 3) fail("'space directions' has " + std::to_string(items.size()) + " vectors, expected 3");
            for (int a = 0; a < 3; ++a) {
                if (items[std::size_t(a)] == "none")
                    fail("axis " + std::to_string(a) + " has no space direction ('none'): not a spatial volume");
                dvec3 d = vector3(name, items[std::size_t(a)]);
                if (!(glm::length(d) > 0.0))
                    fail("space direction of axis " + std::to_string(a) + " has zero length (spacing must be positive)");
                h_.directions[a] = d;
            }
            h_.hasDirections = true;
        } else if (name == "space origin") {
            h_.origin = vector3(name, value);
            h_.hasOrigin = true;
        } else if (name == "axis mins" || name == "axismins") {
            auto w = words(value);
            dvec3 o(0.0);
            bool all = w.size() == 3;
            for (std::size_t a = 0; all && a < 3; ++a) {
                bool ok = false;
                o[int(a)] = toDouble(w[a], ok);
                all = ok && std::isfinite(o[int(a)]);
            }
            if (all && !h_.hasOrigin) { h_.origin = o; h_.hasOrigin = true; }
        } else if (name == "space") {
            h_.space = value;
            if (lower(value).find("time") != std::string::npos)
                fail("space '" + value + "' has a time axis, only 3-D space is supported");
        } else if (name == "space dimension") {
            if (std::atoi(value.c_str()) != 3) fail("'space dimension' must be 3, is " + value);
        } else if (name == "kinds") {
            for (const auto& k : words(value)) {
                std::string l = lower(k);
                if (l != "domain" && l != "space" && l != "???" && l != "none")
                    fail("axis kind '" + k + "' is not a spatial axis: only scalar volumes are supported");
            }
        } else if (name == "byte skip" || name == "byteskip" || name == "line skip" || name == "lineskip") {
            if (std::atol(value.c_str()) != 0) fail("'" + name + ": " + value + "' is not supported");
        } else if (name == "content") {
            h_.content = value;
        } else if (name == "data file" || name == "datafile") {
            dataFile(value);
        }
        // Every other field (units, labels, centers, min, max, ...) does not change the samples.
    }

    void dataFile(const std::string& value) {
        auto w = words(value);
        if (w.empty()) fail("'data file' is empty");
        if (w[0] == "LIST") {
            listMode_ = true;
            return;  // the file names follow, one per line
        }
        if (w.size() >= 4) {
            if (!safeIntegerPattern(w[0]))
                fail("data file pattern '" + w[0] + "' must hold exactly one integer conversion like %03d (width at most " +
                     std::to_string(kMaxPatternWidth) + ")");
            if (w.size() > 4 && std::atoi(w[4].c_str()) != 3)
                fail("data file pattern splits along axis " + w[4] + ", only slices along the last axis are supported");
            // Bounded so that neither this loop nor vtkNrrdReader's own (on int) can overflow.
            constexpr long long kLimit = 1000000000;
            long long lo = 0, hi = 0, step = 0;
            if (!boundedInteger(w[1], kLimit, lo) || !boundedInteger(w[2], kLimit, hi) ||
                !boundedInteger(w[3], kLimit, step) || step <= 0 || hi < lo || (hi - lo) / step >= 1000000)
                fail("data file pattern range " + w[1] + " " + w[2] + " " + w[3] +
                     " is invalid (MIN MAX STEP: integers within +-10^9, MIN <= MAX, STEP > 0, under a million files)");
            for (long long i = lo; i <= hi; i += step) {
                char name[4096];
                std::snprintf(name, sizeof name, w[0].c_str(), int(i));
                addDataFile(name);
            }
            return;
        }
        addDataFile(value);
    }

    void addDataFile(const std::string& name) {
        fs::path p(name);
        if (p.is_relative()) p = fs::path(h_.path).parent_path() / p;
        h_.dataFiles.push_back(p.lexically_normal().string());
    }

    bool listMode_ = false;

private:
    NrrdHeader& h_;
};

}  // namespace

NrrdHeader NrrdHeader::parse(const std::string& path) {
    NrrdHeader h;
    h.path = path;
    std::string text = readPrefix(path, 1u << 16);
    if (text.find("\n\n") == std::string::npos && text.find("\n\r\n") == std::string::npos && text.size() == (1u << 16))
        text = readPrefix(path, kMaxHeaderBytes);
    if (text.empty()) throw FileError(path + ": file is empty (0 bytes)");
    if (text.rfind("NRRD000", 0) != 0 || text.size() < 8 || text[7] < '1' || text[7] > '5')
        throw FormatNotSupported(path + ": not a NRRD file: it starts with '" + quoteBytes(text.substr(0, 8)) +
                                 "', expected 'NRRD0001'..'NRRD0005'");
    h.magic = text.substr(0, 8);

    Parser parser(h);
    std::size_t pos = text.find('\n');
    parser.requireText(text.substr(0, pos), 1);
    bool blankLineSeen = false;
    int lineNo = 1;
    while (pos != std::string::npos && pos + 1 < text.size()) {
        std::size_t start = pos + 1;
        pos = text.find('\n', start);
        std::string line = text.substr(start, pos == std::string::npos ? std::string::npos : pos - start);
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        parser.requireText(line, lineNo);
        if (line.empty()) {
            blankLineSeen = true;
            h.headerBytes = pos == std::string::npos ? text.size() : pos + 1;
            break;
        }
        if (parser.listMode_) {
            parser.addDataFile(trim(line));
            continue;
        }
        if (line[0] == '#') continue;
        auto kv = line.find(":=");
        auto fd = line.find(": ");
        if (kv != std::string::npos && (fd == std::string::npos || kv < fd)) {
            h.keyValues[line.substr(0, kv)] = line.substr(kv + 2);
        } else if (fd != std::string::npos) {
            parser.field(line.substr(0, fd), trim(line.substr(fd + 2)));
        } else {
            parser.fail("header line " + std::to_string(lineNo) + " is neither 'field: value' nor 'key:=value': '" +
                        quoteBytes(line.substr(0, 60)) + "'");
        }
    }

    if (h.dimension == 0) parser.fail("header has no 'dimension' field");
    if (h.sizes.x == 0) parser.fail("header has no 'sizes' field");
    if (double(h.sizes.x) * double(h.sizes.y) * double(h.sizes.z) > kMaxSamples)
        parser.fail("sizes " + std::to_string(h.sizes.x) + " x " + std::to_string(h.sizes.y) + " x " +
                    std::to_string(h.sizes.z) + " exceed the supported 2^32 samples");
    if (h.type.empty()) parser.fail("header has no 'type' field");
    if (h.encoding.empty()) parser.fail("header has no 'encoding' field");
    if (h.dataFiles.empty() && !blankLineSeen)
        parser.fail("header is not followed by a blank line and data (and names no 'data file')");
    if (h.endian.empty() && h.typeSize > 1 && h.encoding != "ascii") {
        log::warning(path + ": no 'endian' field, assuming little");
        h.endian = "little";
    }
    if (h.hasDirections && h.hasSpacings)
        log::warning(path + ": both 'spacings' and 'space directions' given, using 'space directions'");
    return h;
}

void NrrdHeader::checkData() const {
    auto fail = [&](const std::string& what) { throw FileError(path + ": " + what); };
    std::vector<std::string> files = dataFiles.empty() ? std::vector<std::string>{path} : dataFiles;
    std::size_t offset = dataFiles.empty() ? headerBytes : 0;
    for (const auto& f : files) {
        std::error_code ec;
        if (!fs::is_regular_file(f, ec)) fail("data file '" + f + "' not found");
    }
    // vtkNrrdReader reads split data as one 2-D slice per file and indexes its file list by
    // slice: with fewer files than slices it read past the end of that list and crashed.
    if (files.size() > 1 && std::size_t(sizes.z) != files.size())
        fail("header lists " + std::to_string(files.size()) + " data files for " + std::to_string(sizes.z) +
             " slices along the last axis (split data must hold one slice per file)");
    if (files.size() > 1 && sizes.x <= 9)
        fail("slices split into several files need more than 9 samples along the first axis");
    std::size_t perFile = sampleCount() / files.size();
    std::string shape = std::to_string(sizes.x) + "x" + std::to_string(sizes.y) + "x" + std::to_string(sizes.z) + " " + type;

    if (encoding == "raw") {
        std::uintmax_t need = std::uintmax_t(perFile) * typeSize;
        for (const auto& f : files) {
            std::uintmax_t size = fileSize(f);
            std::uintmax_t have = size > offset ? size - offset : 0;
            if (have < need) {
                std::string where = f == path ? "the file has " : "data file '" + f + "' has ";
                fail("data truncated: header says " + shape + " = " + std::to_string(need) + " bytes of data" +
                     (files.size() > 1 ? " per file" : "") + ", " + where + std::to_string(have));
            }
        }
    } else if (encoding == "ascii") {
        std::size_t count = 0;
        for (const auto& f : files) {
            std::ifstream in(f, std::ios::binary);
            in.seekg(std::streamoff(offset));
            for (std::string tok; count < sampleCount() && in >> tok;) ++count;
        }
        if (count < sampleCount())
            fail("data truncated: header says " + shape + " = " + std::to_string(sampleCount()) +
                 " ascii values, found " + std::to_string(count));
    } else if (encoding == "gzip") {
        // The exact length is known only after inflating (NrrdReader checks what VTK reports),
        // but deflate expands at most 1032:1, so a header announcing more than that is refused
        // here, before VTK allocates the announced volume (a 1 KB file could ask for 32 GiB).
        constexpr std::uintmax_t kMaxDeflateRatio = 1032;
        std::uintmax_t need = std::uintmax_t(perFile) * typeSize;
        for (const auto& f : files) {
            std::uintmax_t size = fileSize(f);
            std::uintmax_t have = size > offset ? size - offset : 0;
            if (need / kMaxDeflateRatio > have) {
                std::string where = f == path ? "the file's " : "data file '" + f + "': its ";
                fail("gzip data truncated: header says " + shape + " = " + std::to_string(need) + " bytes" +
                     (files.size() > 1 ? " per file" : "") + ", " + where + std::to_string(have) +
                     " bytes of gzip data inflate to at most " + std::to_string(have * kMaxDeflateRatio) +
                     " (deflate expands at most 1032:1)");
            }
        }
    }
}

}  // namespace octrace::io::detail

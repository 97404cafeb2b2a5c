#include "octrace/io/SphereReader.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <vector>

namespace octrace::io {
namespace {

struct ElementData {
    const char* symbol;
    double radius;  // Bondi (1964), angstroms; 0: not in Bondi's table
    float r, g, b;  // Jmol CPK colour, sRGB 0..255
};

// Bondi, J. Phys. Chem. 68 (1964) 441, table I (the radii his paper recommends), and Jmol's
// element colours. Elements Bondi gives no radius for are listed for their colour only.
constexpr ElementData kElements[] = {
    {"H", 1.20, 255, 255, 255},  {"He", 1.40, 217, 255, 255}, {"Li", 1.82, 204, 128, 255}, {"C", 1.70, 144, 144, 144},
    {"N", 1.55, 48, 80, 248},    {"O", 1.52, 255, 13, 13},    {"F", 1.47, 144, 224, 80},   {"Ne", 1.54, 179, 227, 245},
    {"Na", 2.27, 171, 92, 242},  {"Mg", 1.73, 138, 255, 0},   {"Si", 2.10, 240, 200, 160}, {"P", 1.80, 255, 128, 0},
    {"S", 1.80, 255, 255, 48},   {"Cl", 1.75, 31, 240, 31},   {"Ar", 1.88, 128, 209, 227}, {"K", 2.75, 143, 64, 212},
    {"Ni", 1.63, 80, 208, 80},   {"Cu", 1.40, 200, 128, 51},  {"Zn", 1.39, 125, 128, 176}, {"Ga", 1.87, 194, 143, 143},
    {"As", 1.85, 189, 128, 227}, {"Se", 1.90, 255, 161, 0},   {"Br", 1.85, 166, 41, 41},   {"Kr", 2.02, 92, 184, 209},
    {"Pd", 1.63, 0, 105, 133},   {"Ag", 1.72, 192, 192, 192}, {"Cd", 1.58, 255, 217, 143}, {"In", 1.93, 166, 117, 115},
    {"Sn", 2.17, 102, 128, 128}, {"Te", 2.06, 212, 122, 0},   {"I", 1.98, 148, 0, 148},    {"Xe", 2.16, 66, 158, 176},
    {"Pt", 1.72, 208, 208, 224}, {"Au", 1.66, 255, 209, 35},  {"Hg", 1.55, 184, 184, 208}, {"Tl", 1.96, 166, 84, 77},
    {"Pb", 2.02, 87, 89, 97},    {"U", 1.86, 0, 143, 255},    {"Fe", 0.0, 224, 102, 51},   {"Ca", 0.0, 61, 255, 0},
    {"Mn", 0.0, 156, 122, 199},  {"Co", 0.0, 240, 144, 160},  {"B", 0.0, 255, 181, 181},   {"Al", 0.0, 191, 166, 166},
    {"Mo", 0.0, 84, 181, 181},   {"W", 0.0, 33, 148, 214},    {"Cr", 0.0, 138, 153, 199},  {"V", 0.0, 166, 166, 171},
    {"Ti", 0.0, 191, 194, 199},  {"Cs", 0.0, 87, 23, 143},    {"Rb", 0.0, 112, 46, 176},   {"Sr", 0.0, 0, 255, 0},
    {"Ba", 0.0, 0, 201, 0},      {"D", 1.20, 255, 255, 192},
};
constexpr double kFallbackRadius = 2.0;

const ElementData* findElement(std::string_view e) {
    if (e.empty() || e.size() > 2) return nullptr;
    for (const ElementData& d : kElements) {
        const std::string_view s(d.symbol);
        if (s.size() == e.size() && std::toupper(static_cast<unsigned char>(s[0])) == std::toupper(static_cast<unsigned char>(e[0])) &&
            (s.size() == 1 || std::tolower(static_cast<unsigned char>(s[1])) == std::tolower(static_cast<unsigned char>(e[1]))))
            return &d;
    }
    return nullptr;
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

std::string_view trimView(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

std::optional<double> parseDouble(std::string_view s) {
    s = trimView(s);
    if (s.empty()) return std::nullopt;
    if (s.front() == '+') s.remove_prefix(1);
    double v = 0.0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

/// The element of an atom whose element field is blank: from the atom name (PDB columns
/// 13-16, where the symbol is right-justified in the first two).
std::string elementFromAtomName(std::string_view name) {
    std::string letters;
    for (char c : name.substr(0, std::min<std::size_t>(2, name.size())))
        if (std::isalpha(static_cast<unsigned char>(c))) letters += c;
    if (letters.size() == 2 && !findElement(letters)) letters.erase(1);  // "CA" read as C when no such element
    return letters;
}

/// Adds one atom; the set's notes say afterwards which elements took the fallback radius.
class AtomSink {
public:
    AtomSink(SphereSet& set) : set_(set) {}
    void add(const std::string& name, std::size_t line, std::string_view element, double x, double y, double z) {
        bool known = false;
        const double r = vanDerWaalsRadius(element, &known);
        if (!known) {
            std::string e(element.empty() ? std::string("(none)") : std::string(element));
            if (std::find(fallback_.begin(), fallback_.end(), e) == fallback_.end()) fallback_.push_back(e);
        }
        Sphere s;
        s.centre = dvec3(x, y, z);
        s.radius = r;
        s.colour = elementColour(element);
        const double lim = ScalarField::kMaxWorldCoordinate;
        if (!(std::abs(x) < lim && std::abs(y) < lim && std::abs(z) < lim))
            throw FileError(name + ": line " + std::to_string(line) + ": atom coordinates beyond the supported +-" + detail::num(lim));
        set_.spheres.push_back(s);
    }
    void finish() {
        if (fallback_.empty()) return;
        std::string list;
        for (const auto& e : fallback_) list += (list.empty() ? "" : ", ") + e;
        set_.notes.push_back("van der Waals radius " + detail::num(kFallbackRadius) + " A (not in Bondi 1964) for: " + list);
    }

private:
    SphereSet& set_;
    std::vector<std::string> fallback_;
};

void checkCount(const std::string& name, std::uint64_t atoms, std::uint64_t memoryBudget) {
    if (atoms > kMaxSpheres)
        throw LimitError(name + ": " + std::to_string(atoms) + " atom records, more than the " + std::to_string(kMaxSpheres) +
                         " spheres octrace handles");
    checkMemoryBudget(name + ": " + std::to_string(atoms) + " atoms", saturatingMultiply(atoms, sizeof(Sphere)), memoryBudget);
}

/// Calls f(line, lineNumber) for each line (without its end).
template <class F>
void forEachLine(std::string_view text, F&& f) {
    std::size_t pos = 0, number = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (!f(line, ++number)) return;
        pos = end + 1;
    }
}

bool isAtomRecord(std::string_view line) { return line.starts_with("ATOM  ") || line.starts_with("HETATM") || line == "ATOM" || line == "HETATM"; }

// ---- PDB -------------------------------------------------------------------------------

void parsePdb(std::string_view text, const std::string& name, std::uint64_t memoryBudget, SphereSet& set) {
    std::uint64_t count = 0;
    forEachLine(text, [&](std::string_view line, std::size_t) {
        count += isAtomRecord(line);
        return true;
    });
    if (count == 0) throw FileError(name + ": no atoms (no ATOM or HETATM record)");
    checkCount(name, count, memoryBudget);
    set.spheres.reserve(std::size_t(count));
    AtomSink sink(set);
    char altLoc = 0;  // the first alternate location met
    bool ended = false;
    forEachLine(text, [&](std::string_view line, std::size_t number) {
        if (line.starts_with("ENDMDL")) {
            ended = !set.spheres.empty();  // the first model with atoms is the one drawn
            return !ended;
        }
        if (!isAtomRecord(line)) return true;
        const std::string where = name + ": line " + std::to_string(number) + ": " + std::string(trimView(line.substr(0, 6))) + " record";
        if (line.size() < 54)
            throw FileError(where + " is " + std::to_string(line.size()) + " characters long, its coordinates end at column 54");
        const char alt = line[16];
        if (alt != ' ') {
            if (!altLoc) altLoc = alt;
            if (alt != altLoc) return true;
        }
        static constexpr const char* kAxis[] = {"x (columns 31-38)", "y (columns 39-46)", "z (columns 47-54)"};
        double c[3];
        for (int a = 0; a < 3; ++a) {
            const std::string_view field = line.substr(std::size_t(30 + 8 * a), 8);
            auto v = parseDouble(field);
            if (!v) throw FileError(where + ": coordinate " + kAxis[a] + " '" + detail::quoteBytes(std::string(field)) + "' is not a finite number");
            c[a] = *v;
        }
        std::string element = line.size() >= 78 ? std::string(trimView(line.substr(76, 2))) : std::string();
        if (element.empty()) element = elementFromAtomName(line.substr(12, 4));
        sink.add(name, number, element, c[0], c[1], c[2]);
        return true;
    });
    sink.finish();
    set.notes.push_back("PDB: " + std::to_string(set.spheres.size()) + " atoms" + (altLoc ? std::string(", alternate location ") + altLoc : std::string()));
}

// ---- mmCIF -----------------------------------------------------------------------------

/// STAR/CIF tokens: white-space separated words, '...' and "..." (closed by the quote before
/// white space), ;-delimited text fields, # comments.
class CifTokens {
public:
    struct Token {
        std::string_view text;
        std::size_t line = 0;
        bool quoted = false;  // a value that cannot be a keyword
    };
    CifTokens(std::string_view text, const std::string& name) : s_(text), name_(name) {}
    bool next(Token& t) {
        for (;;) {
            while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
                if (s_[pos_] == '\n') ++line_;
                ++pos_;
            }
            if (pos_ >= s_.size()) return false;
            if (s_[pos_] == '#') {
                while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
                continue;
            }
            break;
        }
        t.line = line_;
        t.quoted = false;
        const char c = s_[pos_];
        const bool lineStart = pos_ == 0 || s_[pos_ - 1] == '\n';
        if (c == ';' && lineStart) {
            const std::size_t start = pos_ + 1;
            std::size_t end = s_.find("\n;", pos_);
            if (end == std::string_view::npos) throw FileError(name_ + ": line " + std::to_string(line_) + ": text field (;) not closed");
            for (std::size_t i = pos_; i < end + 1; ++i) line_ += s_[i] == '\n';
            t.text = s_.substr(start, end - start);
            t.quoted = true;
            pos_ = end + 2;
            return true;
        }
        if (c == '\'' || c == '"') {
            std::size_t i = pos_ + 1;
            for (;; ++i) {
                if (i >= s_.size() || s_[i] == '\n')
                    throw FileError(name_ + ": line " + std::to_string(line_) + ": quoted value not closed on its line");
                if (s_[i] == c && (i + 1 >= s_.size() || std::isspace(static_cast<unsigned char>(s_[i + 1])))) break;
            }
            t.text = s_.substr(pos_ + 1, i - pos_ - 1);
            t.quoted = true;
            pos_ = i + 1;
            return true;
        }
        const std::size_t start = pos_;
        while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
        t.text = s_.substr(start, pos_ - start);
        return true;
    }
    std::size_t line() const { return line_; }

private:
    std::string_view s_;
    const std::string& name_;
    std::size_t pos_ = 0, line_ = 1;
};

bool iequalsPrefix(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i]))) return false;
    return true;
}
bool iequals(std::string_view a, std::string_view b) { return a.size() == b.size() && iequalsPrefix(a, b); }
bool isKeyword(const CifTokens::Token& t) {
    return !t.quoted && (t.text.starts_with('_') || iequals(t.text, "loop_") || iequalsPrefix(t.text, "data_") ||
                         iequalsPrefix(t.text, "save_") || iequals(t.text, "stop_") || iequals(t.text, "global_"));
}

/// The _atom_site category: its item names (without the prefix) and the values, row by row.
/// `visit(row)` gets the values of one row; returns the number of rows.
template <class F>
std::uint64_t forEachAtomSiteRow(std::string_view text, const std::string& name, F&& visit) {
    CifTokens tok(text, name);
    CifTokens::Token t;
    bool have = tok.next(t);
    std::uint64_t rows = 0;
    std::vector<std::string_view> tags;
    std::vector<CifTokens::Token> row;
    bool seen = false;
    while (have) {
        if (!t.quoted && iequals(t.text, "loop_")) {
            tags.clear();
            while ((have = tok.next(t)) && !t.quoted && t.text.starts_with('_')) tags.push_back(t.text);
            const bool atoms = !tags.empty() && iequalsPrefix(tags[0], "_atom_site.");
            std::size_t k = 0;
            while (have && !isKeyword(t)) {
                if (atoms) {
                    if (k == 0) row.clear();
                    row.push_back(t);
                    if (++k == tags.size()) {
                        visit(tags, row);
                        ++rows;
                        k = 0;
                    }
                }
                have = tok.next(t);
            }
            if (atoms) {
                if (seen) throw FileError(name + ": two _atom_site loops");
                seen = true;
                if (k != 0)
                    throw FileError(name + ": line " + std::to_string(row.front().line) + ": the _atom_site loop ends inside a row (" +
                                    std::to_string(k) + " of " + std::to_string(tags.size()) + " values)");
            }
            continue;
        }
        if (!t.quoted && iequalsPrefix(t.text, "_atom_site.")) {
            // One atom written as item-value pairs, outside a loop.
            if (seen) throw FileError(name + ": line " + std::to_string(t.line) + ": _atom_site items both in a loop and outside one");
            tags.clear();
            row.clear();
            while (have && !t.quoted && iequalsPrefix(t.text, "_atom_site.")) {
                tags.push_back(t.text);
                if (!(have = tok.next(t)) || isKeyword(t))
                    throw FileError(name + ": line " + std::to_string(tok.line()) + ": item " + std::string(tags.back()) + " has no value");
                row.push_back(t);
                have = tok.next(t);
            }
            visit(tags, row);
            ++rows;
            seen = true;
            continue;
        }
        have = tok.next(t);
    }
    return rows;
}

void parseCif(std::string_view text, const std::string& name, std::uint64_t memoryBudget, SphereSet& set) {
    const std::uint64_t count = forEachAtomSiteRow(text, name, [](const auto&, const auto&) {});
    if (count == 0) throw FileError(name + ": no atoms (no _atom_site rows)");
    checkCount(name, count, memoryBudget);
    set.spheres.reserve(std::size_t(count));
    AtomSink sink(set);
    std::string altLoc, model;
    forEachAtomSiteRow(text, name, [&](const std::vector<std::string_view>& tags, const std::vector<CifTokens::Token>& row) {
        auto find = [&](std::string_view item) -> const CifTokens::Token* {
            for (std::size_t i = 0; i < tags.size(); ++i)
                if (tags[i].size() > 11 && iequalsPrefix(tags[i], "_atom_site.") && iequals(tags[i].substr(11), item)) return &row[i];
            return nullptr;
        };
        auto unknown = [](const CifTokens::Token* v) { return !v || (!v->quoted && (v->text == "." || v->text == "?")); };
        const std::size_t line = row.front().line;
        if (const auto* m = find("pdbx_PDB_model_num"); !unknown(m)) {
            if (model.empty()) model = std::string(m->text);
            if (m->text != model) return;
        }
        if (const auto* a = find("label_alt_id"); !unknown(a)) {
            if (altLoc.empty()) altLoc = std::string(a->text);
            if (a->text != altLoc) return;
        }
        double c[3];
        static constexpr const char* kItems[] = {"Cartn_x", "Cartn_y", "Cartn_z"};
        for (int a = 0; a < 3; ++a) {
            const auto* v = find(kItems[a]);
            if (!v) throw FileError(name + ": the _atom_site category has no " + kItems[a] + " item");
            auto d = parseDouble(v->text);
            if (!d)
                throw FileError(name + ": line " + std::to_string(line) + ": _atom_site." + kItems[a] + " '" +
                                detail::quoteBytes(std::string(v->text.substr(0, 40))) + "' is not a finite number");
            c[a] = *d;
        }
        std::string element;
        if (const auto* e = find("type_symbol"); !unknown(e)) element = std::string(e->text);
        else if (const auto* n = find("label_atom_id"); !unknown(n)) element = elementFromAtomName(n->text);
        sink.add(name, line, element, c[0], c[1], c[2]);
    });
    sink.finish();
    set.notes.push_back("mmCIF: " + std::to_string(set.spheres.size()) + " atoms" +
                        (model.empty() ? std::string() : ", model " + model) + (altLoc.empty() ? std::string() : ", alternate location " + altLoc));
}

bool looksLikeCif(std::string_view text) {
    bool cif = false;
    forEachLine(text, [&](std::string_view line, std::size_t) {
        line = trimView(line);
        if (line.empty() || line.front() == '#') return true;
        cif = iequalsPrefix(line, "data_");
        return false;  // the first meaningful line decides
    });
    return cif;
}

}  // namespace

bool isMoleculeFile(const std::string& path) {
    const std::string ext = detail::lower(std::filesystem::path(path).extension().string());
    return ext == ".pdb" || ext == ".ent" || ext == ".cif" || ext == ".mmcif";
}

double vanDerWaalsRadius(std::string_view element, bool* known) {
    const ElementData* d = findElement(element);
    const bool k = d && d->radius > 0.0;
    if (known) *known = k;
    return k ? d->radius : kFallbackRadius;
}

vec3 elementColour(std::string_view element) {
    const ElementData* d = findElement(element);
    const vec3 srgb = d ? vec3(d->r, d->g, d->b) / 255.0f : vec3(1.0f, 20.0f / 255.0f, 147.0f / 255.0f);
    return vec3(srgbToLinear(srgb.r), srgbToLinear(srgb.g), srgbToLinear(srgb.b));
}

SphereSet parseMolecule(std::string_view text, const std::string& name, std::uint64_t memoryBudget) {
    if (text.empty()) throw FileError(name + ": file is empty (0 bytes)");
    SphereSet set;
    set.source = name;
    set.units = "angstrom";
    set.name = std::filesystem::path(name).stem().string();
    if (looksLikeCif(text)) parseCif(text, name, memoryBudget, set);
    else parsePdb(text, name, memoryBudget, set);
    set.validate();
    return set;
}

SphereSet readMolecule(const std::string& path, std::uint64_t memoryBudget) {
    detail::requireReadableFile(path);
    const std::uint64_t size = detail::fileSize(path);
    checkMemoryBudget(path + ": reading " + std::to_string(size) + " bytes", size, memoryBudget);
    std::ifstream in(path, std::ios::binary);
    std::string text(std::size_t(size), '\0');
    in.read(text.data(), std::streamsize(size));
    if (std::uint64_t(in.gcount()) != size) throw InputError(path + ": cannot be read");
    return parseMolecule(text, path, memoryBudget);
}

}  // namespace octrace::io

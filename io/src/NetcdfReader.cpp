#include "octrace/io/NetcdfReader.h"

#include "FormatSniffer.h"
#include "GeoAxis.h"
#include "GeoGrid.h"
#include "InputFile.h"
#include "NetcdfClassicHeader.h"
#include "NetcdfFile.h"
#include "NetcdfInterpretation.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace octrace::io {
namespace {

using namespace detail;

// A sample's float and mask byte, and the double GDAL reads it into.
constexpr std::uint64_t kReadBytesPerSample = sizeof(float) + 1 + sizeof(double);

// Checks the signature (and, for classic files, that the data the header announces are all
// there); returns the format's name.
std::string openNetcdf(const std::string& path) {
    Sniffed s = sniffFormat(path);
    if (s.kind != FileKind::NetCdf)
        throw FormatNotSupported(path + ": not a NetCDF file: it starts with '" + quoteBytes(readPrefix(path, 8)) +
                                 "', expected 'CDF\\x01', 'CDF\\x02', 'CDF\\x05' or the HDF5 signature");
    if (s.description.rfind("NetCDF-3", 0) == 0) {
        std::uint64_t need = classicDataEnd(path), have = fileSize(path);
        if (have < need)
            throw FileError(path + ": NetCDF data truncated: the header places data up to byte " + std::to_string(need) +
                            ", the file has " + std::to_string(have) + " bytes");
    }
    return s.description;
}

std::string listOf(const std::vector<const VariableInfo*>& vars) {
    std::string s;
    for (const auto* v : vars) s += (s.empty() ? "" : ", ") + v->signature();
    return s.empty() ? std::string("none") : s;
}

std::vector<const VariableInfo*> dataVariables(const NetcdfFile& file) {
    std::vector<const VariableInfo*> out;
    for (const auto& v : file.variables())
        if (v.numeric && !v.coordinate) out.push_back(&v);
    return out;
}

// Variables with at least 3 dimensions longer than 1 (a 4-D one is read at its first time step).
std::vector<const VariableInfo*> volumes(const NetcdfFile& file) {
    std::vector<const VariableInfo*> out;
    for (const auto* v : dataVariables(file))
        if (v->extent() >= 3) out.push_back(v);
    return out;
}

const VariableInfo& chooseVariable(const std::string& path, const NetcdfFile& file, const std::string& wanted) {
    auto data = dataVariables(file);
    if (wanted.empty()) {
        auto vols = volumes(file);
        if (vols.size() == 1) return *vols[0];
        if (vols.empty()) throw InputError(path + ": no 3-D variable (variables: " + listOf(data) + ")");
        std::string names;
        for (const auto* v : vols) names += (names.empty() ? "" : ", ") + v->shortName;
        throw InputError(path + ": several 3-D variables (" + names + "); choose one with --var");
    }
    std::vector<const VariableInfo*> hits;
    for (const auto& v : file.variables())
        if (v.name == wanted || v.shortName == wanted) hits.push_back(&v);
    if (hits.empty()) throw InputError(path + ": no variable '" + wanted + "' (variables: " + listOf(data) + ")");
    if (hits.size() > 1)
        throw InputError(path + ": variable name '" + wanted + "' is ambiguous, use its full name (" + hits[0]->name +
                         ", ...)");
    if (!hits[0]->numeric) throw InputError(path + ": variable '" + wanted + "' is not numeric");
    return *hits[0];
}

// The grid of one variable: which of its dimensions are x, y, z and which samples they take.
struct Layout {
    std::array<std::size_t, 3> dim{};
    std::array<AxisSelection, 3> axes;
    std::vector<std::string> notes;
};

Layout layoutFor(const std::string& path, const NetcdfFile& file, const VariableInfo& var, const FieldRequest& req) {
    std::vector<std::size_t> spread;  // dimensions with more than one sample
    for (std::size_t d = 0; d < var.dimSizes.size(); ++d)
        if (var.dimSizes[d] > 1) spread.push_back(d);
    if (spread.size() < 3)
        throw InputError(path + ": variable " + var.signature() + " has " + std::to_string(spread.size()) +
                         " dimension(s) longer than 1, a 3-D field is needed");

    std::vector<AxisInfo> info(var.dimSizes.size());
    std::vector<AxisClass> cls(var.dimSizes.size());
    for (std::size_t d : spread) {
        info[d] = file.axis(var, d);
        cls[d] = classifyAxis(info[d]);
    }
    auto find = [&](AxisRole r) {
        std::vector<std::size_t> hits;
        for (std::size_t d : spread)
            if (cls[d].role == r) hits.push_back(d);
        return hits;
    };
    auto lon = find(AxisRole::Longitude), lat = find(AxisRole::Latitude), vert = find(AxisRole::Vertical);
    bool geographic = lon.size() == 1 && lat.size() == 1 && vert.size() == 1 && !info[lon[0]].values.empty() &&
                      !info[lat[0]].values.empty() && !info[vert[0]].values.empty();

    std::vector<std::size_t> spatial;
    if (geographic) spatial = {vert[0], lat[0], lon[0]};
    else spatial.assign(spread.end() - 3, spread.end());  // the three fastest-varying dimensions
    std::sort(spatial.begin(), spatial.end());

    Layout L;
    for (std::size_t d : spread) {
        if (std::find(spatial.begin(), spatial.end(), d) != spatial.end()) continue;
        std::string msg = "dimension '" + var.dimNames[d] + "' (" + roleName(cls[d].role) + "): first of " +
                          std::to_string(var.dimSizes[d]) + " steps used";
        log::warning(path + ": variable '" + var.shortName + "': " + msg);
        L.notes.push_back(msg);
    }
    for (std::size_t d : spatial)
        if (cls[d].role == AxisRole::Time)
            throw InputError(path + ": variable " + var.signature() + " has no 3 spatial axes ('" + var.dimNames[d] +
                             "' is time)");

    if (geographic) {
        const AxisClass& vc = cls[vert[0]];
        std::vector<double> depthKm;
        for (double v : info[vert[0]].values) depthKm.push_back(v * vc.toKm * (vc.positiveDown ? 1.0 : -1.0));
        GeoMapping m = mapGeographic(path, info[lon[0]].values, info[lat[0]].values, depthKm, req);
        L.dim = {lon[0], lat[0], vert[0]};
        L.axes = {std::move(m.x), std::move(m.y), std::move(m.z)};
        L.notes.insert(L.notes.end(), m.notes.begin(), m.notes.end());
        if (!vc.note.empty()) L.notes.push_back(vc.note);
        return L;
    }

    if (req.hasRegion)
        throw InputError(path + ": a region needs a longitude/latitude/depth grid; variable " + var.signature() +
                         " has axes " + roleName(cls[spatial[0]].role) + ", " + roleName(cls[spatial[1]].role) + ", " +
                         roleName(cls[spatial[2]].role));
    if (req.verticalScale != 0.0)
        log::warning(path + ": vertical scale ignored, variable '" + var.shortName + "' is not on a geographic grid");
    L.dim = {spatial[2], spatial[1], spatial[0]};  // x varies fastest
    std::string axes;
    for (int a = 0; a < 3; ++a) {
        const AxisInfo& ai = info[L.dim[std::size_t(a)]];
        std::vector<double> values = ai.values;
        if (values.empty())
            for (std::size_t n = 0; n < ai.size; ++n) values.push_back(double(n));
        L.axes[std::size_t(a)] = increasingAxis(path, ai.name, values);
        axes += std::string(a ? ", " : "") + "xyz"[a] + " = " + ai.name +
                (ai.values.empty() ? " (index)" : ai.units.empty() ? "" : " (" + ai.units + ")");
    }
    L.notes.push_back("not a geographic grid: world units are the file's coordinates: " + axes);
    return L;
}

bool uniform(const std::vector<double>& v) {
    if (v.size() < 3) return true;
    double step = (v.back() - v.front()) / double(v.size() - 1);
    for (std::size_t n = 0; n < v.size(); ++n)
        if (std::abs(v[n] - (v.front() + double(n) * step)) > 1e-6 * std::abs(step)) return false;
    return true;
}

// Reads the selected samples, one hyperslab per run of consecutive stored x indices (a
// region across the file's longitude seam is two runs).
void readSamples(const NetcdfFile& file, const VariableInfo& var, const Layout& L, const SampleRules& rules,
                 ScalarField& f) {
    const std::size_t nd = var.dimSizes.size();
    std::vector<std::uint64_t> start(nd, 0);
    std::vector<std::size_t> count(nd, 1);
    for (int a = 1; a < 3; ++a) {
        const auto& s = L.axes[std::size_t(a)].stored;
        auto [lo, hi] = std::minmax_element(s.begin(), s.end());
        start[L.dim[std::size_t(a)]] = *lo;
        count[L.dim[std::size_t(a)]] = *hi - *lo + 1;
    }
    const auto& sx = L.axes[0].stored;
    const auto& sy = L.axes[1].stored;
    const auto& sz = L.axes[2].stored;
    f.values.assign(f.sampleCount(), 0.0f);
    f.valid.assign(f.sampleCount(), 0);
    for (std::size_t i0 = 0; i0 < sx.size();) {
        std::size_t i1 = i0;
        while (i1 + 1 < sx.size() && (sx[i1 + 1] == sx[i1] + 1 || sx[i1 + 1] + 1 == sx[i1]) &&
               (i1 == i0 || (sx[i1 + 1] > sx[i1]) == (sx[i1] > sx[i1 - 1])))
            ++i1;
        std::size_t xlo = std::min(sx[i0], sx[i1]);
        start[L.dim[0]] = xlo;
        count[L.dim[0]] = i1 - i0 + 1;
        std::vector<double> buf = file.read(var, start, count);
        std::vector<std::size_t> stride(nd, 1);
        for (std::size_t d = nd - 1; d > 0; --d) stride[d - 1] = stride[d] * count[d];
        for (std::size_t k = 0; k < sz.size(); ++k)
            for (std::size_t j = 0; j < sy.size(); ++j)
                for (std::size_t i = i0; i <= i1; ++i) {
                    std::size_t at = (sx[i] - xlo) * stride[L.dim[0]] + (sy[j] - start[L.dim[1]]) * stride[L.dim[1]] +
                                     (sz[k] - start[L.dim[2]]) * stride[L.dim[2]];
                    double raw = buf[at];
                    std::size_t idx = f.index(int(i), int(j), int(k));
                    if (!rules.isValid(raw)) continue;
                    float v = float(raw * rules.scale + rules.offset);
                    f.values[idx] = v;
                    f.valid[idx] = std::isfinite(v) ? 1 : 0;
                }
        i0 = i1 + 1;
    }
}

std::string regionText(const FieldRequest& req) {
    return num(req.region[0]) + "," + num(req.region[1]) + "," + num(req.region[2]) + "," + num(req.region[3]);
}

ScalarField readVariable(const std::string& path, const NetcdfFile& file, const VariableInfo& var,
                         const FieldRequest& req) {
    Layout L = layoutFor(path, file, var, req);
    ScalarField f;
    f.source = path;
    f.name = var.shortName;
    f.units = var.units;
    for (int a = 0; a < 3; ++a) {
        const auto& w = L.axes[std::size_t(a)].world;
        f.dims[a] = int(w.size());
        if (uniform(w)) {
            f.origin[a] = w.front();
            f.spacing[a] = (w.back() - w.front()) / double(w.size() - 1);
        } else {
            f.origin[a] = 0.0;
            f.coords[std::size_t(a)] = w;
        }
    }
    if (double(f.dims.x) * double(f.dims.y) * double(f.dims.z) > 4294967296.0)
        throw InputError(path + ": variable '" + var.shortName + "' has more than the supported 2^32 samples" +
                         " in the requested grid; choose a smaller region");
    f.validateGeometry();
    // The samples and their mask, and the hyperslab GDAL reads them into (as double).
    checkMemoryBudget(path + ": reading '" + var.shortName + "' (" + std::to_string(f.dims.x) + "x" +
                          std::to_string(f.dims.y) + "x" + std::to_string(f.dims.z) + " samples)",
                      saturatingMultiply(f.sampleCount(), kReadBytesPerSample), req.memoryBudget);
    readSamples(file, var, L, file.rules(var), f);
    if (!var.longName.empty()) f.notes.push_back(var.shortName + ": " + var.longName);
    f.notes.insert(f.notes.end(), L.notes.begin(), L.notes.end());
    std::size_t valid = f.validCount();
    if (valid == 0)
        throw EmptyResultError(path + ": variable '" + var.shortName + "' has no valid sample" +
                               (req.hasRegion ? " in region " + regionText(req) : std::string()) +
                               " (all missing_value/_FillValue or non-finite)");
    if (valid == f.sampleCount()) f.valid.clear();
    f.validate();
    return f;
}

void describeAxes(std::ostringstream& s, const NetcdfFile& file) {
    s << "dimensions:\n";
    std::vector<std::string> seen;
    for (const auto& v : file.variables())
        for (std::size_t d = 0; d < v.dimNames.size(); ++d) {
            if (std::find(seen.begin(), seen.end(), v.dimNames[d]) != seen.end()) continue;
            seen.push_back(v.dimNames[d]);
            AxisInfo a = file.axis(v, d);
            AxisClass c = classifyAxis(a);
            s << "  " << a.name << " = " << a.size << ": " << roleName(c.role);
            if (c.role == AxisRole::Vertical) s << (c.positiveDown ? " (positive down)" : " (positive up)");
            if (!a.units.empty()) s << ", units '" << a.units << "'";
            if (a.values.empty()) {
                s << ", no coordinate variable\n";
                continue;
            }
            s << ", " << num(a.values.front()) << " .. " << num(a.values.back());
            if (a.values.size() > 1)
                s << (uniform(a.values) ? ", uniform step " + num((a.values.back() - a.values.front()) / double(a.values.size() - 1))
                                        : std::string(", uneven"));
            s << "\n";
        }
}

void describeVariable(std::ostringstream& s, const NetcdfFile& file, const VariableInfo& v, std::uint64_t budget) {
    s << "  " << v.signature() << " " << v.dataType << " [";
    for (std::size_t d = 0; d < v.dimSizes.size(); ++d) s << (d ? " x " : "") << v.dimSizes[d];
    s << "]";
    if (!v.units.empty()) s << ", units '" << v.units << "'";
    if (!v.longName.empty()) s << ", '" << v.longName << "'";
    std::uint64_t total = 1;
    for (auto n : v.dimSizes) total = saturatingMultiply(total, n);
    if (total > 200'000'000u || (budget && saturatingMultiply(total, sizeof(double)) > budget)) {
        s << ", value range not computed (" << total << " samples" << (total > 200'000'000u ? "" : ", over the memory budget")
          << ")\n";
        return;
    }
    std::vector<std::uint64_t> start(v.dimSizes.size(), 0);
    std::vector<double> raw = file.read(v, start, v.dimSizes);
    SampleRules r = file.rules(v);
    double lo = INFINITY, hi = -INFINITY;
    std::size_t valid = 0;
    for (double x : raw) {
        if (!r.isValid(x)) continue;
        double y = x * r.scale + r.offset;
        lo = std::min(lo, y);
        hi = std::max(hi, y);
        ++valid;
    }
    if (valid == 0) s << ": no valid sample";
    else s << ": valid range " << num(lo) << " .. " << num(hi);
    s << " (" << valid << " of " << total << " samples valid)\n";
}

void describeGrid(std::ostringstream& s, const std::string& path, const NetcdfFile& file, std::uint64_t budget) {
    auto vols = volumes(file);
    if (vols.empty()) {
        s << "no 3-D variable: nothing to render\n";
        return;
    }
    s << (vols.size() == 1 ? "grid of " : "grid of the first 3-D variable, ") << vols[0]->shortName << " (whole grid):\n";
    FieldRequest req;
    req.variable = vols[0]->name;
    req.memoryBudget = budget;
    ScalarField f;
    try {
        f = readVariable(path, file, *vols[0], req);
    } catch (const EmptyResultError& e) {
        s << "  " << e.what() << "\n";
        return;
    } catch (const LimitError& e) {
        s << "  " << e.what() << "\n";
        return;
    }
    s << "  dims: " << f.dims.x << " x " << f.dims.y << " x " << f.dims.z << "\n";
    for (int a = 0; a < 3; ++a) {
        s << "  " << "xyz"[a] << ": ";
        if (f.isRectilinear(a))
            s << "rectilinear, " << f.dims[a] << " values " << num(f.coords[std::size_t(a)].front()) << " .. "
              << num(f.coords[std::size_t(a)].back()) << "\n";
        else
            s << "uniform, spacing " << num(f.spacing[a]) << ", from " << num(f.origin[a]) << "\n";
    }
    s << "  origin: (" << num(f.origin.x) << ", " << num(f.origin.y) << ", " << num(f.origin.z) << ")\n";
    Box3 b = f.worldBounds();
    s << "  world bounds: (" << num(b.lo.x) << ", " << num(b.lo.y) << ", " << num(b.lo.z) << ") .. (" << num(b.hi.x)
      << ", " << num(b.hi.y) << ", " << num(b.hi.z) << ")\n";
    for (const auto& n : f.notes) s << "  note: " << n << "\n";
}

}  // namespace

namespace detail {

ScalarField interpretNetcdf(const std::string& path, const FieldRequest& req) {
    if (req.hasRegion) checkRegion(req.region, path);
    if (!(req.verticalScale >= 0.0) || !std::isfinite(req.verticalScale))
        throw UsageError(path + ": vertical scale must be positive (0 = default), got " + num(req.verticalScale));
    NetcdfFile file(path);
    return readVariable(path, file, chooseVariable(path, file, req.variable), req);
}

std::string describeNetcdf(const std::string& path, const std::string& format, std::uint64_t memoryBudget) {
    NetcdfFile file(path);
    std::ostringstream s;
    s << path << "\nformat: " << format << ", read through GDAL's netCDF driver\n";
    describeAxes(s, file);
    s << "variables:\n";
    for (const auto* v : dataVariables(file)) describeVariable(s, file, *v, memoryBudget);
    describeGrid(s, path, file, memoryBudget);
    return s.str();
}

}  // namespace detail

ScalarField NetcdfReader::read(const std::string& path, const FieldRequest& req) {
    openNetcdf(path);
    return interpretNetcdf(path, req);
}

std::string NetcdfReader::describe(const std::string& path, std::uint64_t memoryBudget) {
    return describeNetcdf(path, openNetcdf(path), memoryBudget);
}

std::vector<std::string> NetcdfReader::volumeVariables(const std::string& path) {
    openNetcdf(path);
    NetcdfFile file(path);
    std::vector<std::string> names;
    for (const auto* v : volumes(file)) names.push_back(v->shortName);
    return names;
}

}  // namespace octrace::io

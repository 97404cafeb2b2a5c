#include "netcdf/CfSource.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <cmath>
#include <cstddef>

namespace octrace::io::detail {
namespace {

// NetCDF's default fill values (netcdf.h NC_FILL_*), which mark unwritten samples when a
// variable has no _FillValue. Bytes have none by the NetCDF User's Guide's convention.
bool defaultFill(const std::string& type, double& fill) {
    if (type == "Int16") fill = -32767.0;
    else if (type == "UInt16") fill = 65535.0;
    else if (type == "Int32") fill = -2147483647.0;
    else if (type == "UInt32") fill = 4294967295.0;
    else if (type == "Float32" || type == "Float64") fill = 9.9692099683868690e+36;
    else return false;
    return true;
}

}  // namespace

int VariableInfo::extent() const {
    int n = 0;
    for (auto s : dimSizes) n += s > 1 ? 1 : 0;
    return n;
}

std::string VariableInfo::signature() const {
    std::string s = shortName + "(";
    for (std::size_t d = 0; d < dimNames.size(); ++d) s += (d ? ", " : "") + dimNames[d];
    return s + ")";
}

bool SampleRules::isValid(double raw) const {
    if (!std::isfinite(raw)) return false;
    for (double m : missing)
        if (raw == m || (m != 0.0 && std::abs(raw - m) <= 1e-6 * std::abs(m))) return false;
    return raw >= validMin && raw <= validMax;
}

SampleRules sampleRules(const SampleAttributes& a, const std::string& dataType) {
    SampleRules r;
    r.missing = a.missingValue;
    r.missing.insert(r.missing.end(), a.fillValue.begin(), a.fillValue.end());
    if (a.noData) r.missing.push_back(*a.noData);
    double fill = 0.0;
    if (!a.noData && a.fillValue.empty() && defaultFill(dataType, fill)) r.missing.push_back(fill);
    if (a.validRange.size() == 2) {
        r.validMin = a.validRange[0];
        r.validMax = a.validRange[1];
    }
    if (!a.validMin.empty()) r.validMin = a.validMin[0];
    if (!a.validMax.empty()) r.validMax = a.validMax[0];
    if (a.scale) r.scale = *a.scale;
    if (a.offset) r.offset = *a.offset;
    return r;
}

// CF auxiliary variables: those another variable names as its coordinates or bounds.
void markAuxiliary(std::vector<VariableInfo>& vars) {
    for (const auto& v : vars) {
        auto names = words(v.coordinates);
        if (!v.bounds.empty()) names.push_back(v.bounds);
        for (const auto& n : names)
            for (auto& w : vars)
                if (w.shortName == n && &w != &v) w.auxiliary = true;
    }
}

const VariableInfo* auxiliaryCoordinate(const std::vector<VariableInfo>& vars, const VariableInfo& variable,
                                        const std::string& dim) {
    for (const auto& n : words(variable.coordinates))
        for (const auto& c : vars)
            if (c.shortName == n && c.numeric && c.dimNames.size() == 1 && c.dimNames[0] == dim) return &c;
    return nullptr;
}

void checkAxisLength(const std::string& source, const std::string& dim, std::uint64_t size) {
    if (size > kMaxAxisPoints)
        throw FileError(source + ": dimension '" + dim + "' has " + std::to_string(size) + " points, more than the " +
                        std::to_string(kMaxAxisPoints) + " (2^24) octrace reads along one axis");
}

std::uint64_t hyperslabSamples(const std::string& source, const VariableInfo& variable,
                               const std::vector<std::size_t>& count) {
    std::uint64_t n = 1;
    for (auto c : count) n = saturatingMultiply(n, c);
    if (n > std::uint64_t(std::numeric_limits<std::ptrdiff_t>::max()) / sizeof(double))
        throw FileError(source + ": variable '" + variable.shortName + "' is too large to read (" + std::to_string(n) +
                        " samples)");
    return n;
}

}  // namespace octrace::io::detail

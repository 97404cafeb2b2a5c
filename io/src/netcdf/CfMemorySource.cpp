#include "netcdf/CfMemorySource.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <type_traits>

namespace octrace::io::detail {
namespace {

template <class T>
struct TypeName;
template <> struct TypeName<float> { static constexpr const char* value = "Float32"; };
template <> struct TypeName<double> { static constexpr const char* value = "Float64"; };
template <> struct TypeName<std::int8_t> { static constexpr const char* value = "Int8"; };
template <> struct TypeName<std::uint8_t> { static constexpr const char* value = "Byte"; };
template <> struct TypeName<std::int16_t> { static constexpr const char* value = "Int16"; };
template <> struct TypeName<std::uint16_t> { static constexpr const char* value = "UInt16"; };
template <> struct TypeName<std::int32_t> { static constexpr const char* value = "Int32"; };
template <> struct TypeName<std::uint32_t> { static constexpr const char* value = "UInt32"; };
template <> struct TypeName<std::int64_t> { static constexpr const char* value = "Int64"; };
template <> struct TypeName<std::uint64_t> { static constexpr const char* value = "UInt64"; };

bool hasValues(const CfValues& v) { return !std::holds_alternative<std::monostate>(v); }

std::size_t valueCount(const CfValues& values) {
    return std::visit(
        [](const auto& v) -> std::size_t {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) return 0;
            else return v.size();
        },
        values);
}

// GDAL's name of the element type of `values`.
std::string elementType(const CfValues& values) {
    return std::visit(
        [](const auto& v) -> std::string {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, std::monostate>) return "non-numeric";
            else return TypeName<std::remove_const_t<typename V::value_type>>::value;
        },
        values);
}

// Copies the hyperslab `start` + `count` of a C-order array of `shape` into `out`, as double.
template <class T>
void copyHyperslab(const T* in, const std::vector<std::size_t>& shape, const std::vector<std::uint64_t>& start,
                   const std::vector<std::size_t>& count, double* out) {
    const std::size_t nd = shape.size();
    if (nd == 0) {
        out[0] = double(in[0]);
        return;
    }
    std::vector<std::size_t> stride(nd, 1);
    for (std::size_t d = nd - 1; d > 0; --d) stride[d - 1] = stride[d] * shape[d];
    std::size_t rows = 1;
    for (std::size_t d = 0; d + 1 < nd; ++d) rows *= count[d];
    if (rows == 0 || count[nd - 1] == 0) return;
    std::vector<std::size_t> idx(nd, 0);  // odometer over the outer dimensions
    for (std::size_t r = 0; r < rows; ++r) {
        std::size_t at = std::size_t(start[nd - 1]);
        for (std::size_t d = 0; d + 1 < nd; ++d) at += (std::size_t(start[d]) + idx[d]) * stride[d];
        for (std::size_t i = 0; i < count[nd - 1]; ++i) *out++ = double(in[at + i]);
        for (std::size_t d = nd - 1; d-- > 0;) {
            if (++idx[d] < count[d]) break;
            idx[d] = 0;
        }
    }
}

const CfAttribute* attribute(const CfVariable& v, const char* name) {
    auto it = v.attributes.find(name);
    return it == v.attributes.end() ? nullptr : &it->second;
}

std::string textAttribute(const CfVariable& v, const char* name) {
    const CfAttribute* a = attribute(v, name);
    const auto* s = a ? std::get_if<std::string>(&a->value) : nullptr;
    return s ? *s : std::string();
}

std::vector<double> numberAttribute(const CfVariable& v, const char* name) {
    const CfAttribute* a = attribute(v, name);
    const auto* n = a ? std::get_if<std::vector<double>>(&a->value) : nullptr;
    return n ? *n : std::vector<double>();
}

// A single missing_value as GDAL takes it for the no-data value: one number, or text that is one.
std::optional<double> singleMissingValue(const CfVariable& v) {
    const CfAttribute* a = attribute(v, "missing_value");
    if (!a) return std::nullopt;
    if (const auto* n = std::get_if<std::vector<double>>(&a->value)) {
        if (n->size() == 1) return (*n)[0];
        return std::nullopt;
    }
    const std::string& s = std::get<std::string>(a->value);
    char* end = nullptr;
    double x = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || !trim(end).empty()) return std::nullopt;
    return x;
}

bool equalNoCase(const std::string& a, const char* b) { return lower(a) == lower(b); }

bool oneOfNoCase(const std::string& s, std::initializer_list<const char*> list) {
    for (const char* x : list)
        if (equalNoCase(s, x)) return true;
    return false;
}

// GDAL's netCDF driver's guess of a dimension's type and direction from its indexing variable
// (netCDFDimension, GDAL 3.6), for the cues it takes from attributes: longitude / projection x,
// latitude / projection y, vertical (`positive`, axis Z, length units), time, in that order.
void guessGdalType(const CfVariable& iv, AxisInfo& a) {
    const std::string sn = textAttribute(iv, "standard_name"), axis = trim(textAttribute(iv, "axis"));
    const std::string ln = trim(textAttribute(iv, "long_name")), units = textAttribute(iv, "units");
    const std::string positive = textAttribute(iv, "positive");
    if (equalNoCase(axis, "X") || oneOfNoCase(sn, {"longitude", "projection_x_coordinate", "grid_longitude"}) ||
        equalNoCase(ln, "longitude") ||
        oneOfNoCase(units, {"degrees_east", "degree_east", "degree_E", "degrees_E", "degreeE", "degreesE"})) {
        a.gdalType = "HORIZONTAL_X";
        if (equalNoCase(units, "degrees_east")) a.gdalDirection = "EAST";
    } else if (equalNoCase(axis, "Y") || oneOfNoCase(sn, {"latitude", "projection_y_coordinate", "grid_latitude"}) ||
               equalNoCase(ln, "latitude") ||
               oneOfNoCase(units, {"degrees_north", "degree_north", "degree_N", "degrees_N", "degreeN", "degreesN"})) {
        a.gdalType = "HORIZONTAL_Y";
        if (equalNoCase(units, "degrees_north")) a.gdalDirection = "NORTH";
    } else if (equalNoCase(axis, "Z") || oneOfNoCase(positive, {"up", "down"}) ||
               oneOfNoCase(units, {"m", "meter", "meters", "metre", "metres", "km", "kilometer", "kilometers"})) {
        a.gdalType = "VERTICAL";
        if (equalNoCase(positive, "up")) a.gdalDirection = "UP";
        else if (equalNoCase(positive, "down")) a.gdalDirection = "DOWN";
    } else if (equalNoCase(axis, "T") || equalNoCase(sn, "time") || lower(units).find(" since ") != std::string::npos) {
        a.gdalType = "TEMPORAL";
    }
}

std::string shapeText(const std::vector<std::size_t>& shape) {
    std::string s;
    for (auto n : shape) s += (s.empty() ? "" : " x ") + std::to_string(n);
    return s.empty() ? std::string("scalar") : s;
}

}  // namespace

std::string cfSourceName(const CfDataset& data) {
    return data.description.empty() ? std::string("in-memory dataset") : data.description;
}

CfMemorySource::CfMemorySource(const CfDataset& data) : source_(cfSourceName(data)) {
    std::map<std::string, std::pair<std::size_t, std::string>> dimSize;  // dimension: size, first variable
    std::map<std::string, bool> seen;
    for (const auto& v : data.variables) {
        if (v.name.empty()) throw InputError(source_ + ": a variable has no name");
        if (seen[v.name]) throw InputError(source_ + ": two variables are named '" + v.name + "'");
        seen[v.name] = true;
        const std::string what = source_ + ": variable '" + v.name + "'";
        if (v.dims.size() != v.shape.size())
            throw InputError(what + " has " + std::to_string(v.dims.size()) + " dimension name(s) for a shape of " +
                             std::to_string(v.shape.size()) + " (" + shapeText(v.shape) + ")");
        std::uint64_t n = 1;
        for (std::size_t d = 0; d < v.dims.size(); ++d) {
            n = saturatingMultiply(n, v.shape[d]);
            auto [it, added] = dimSize.try_emplace(v.dims[d], v.shape[d], v.name);
            if (!added && it->second.first != v.shape[d])
                throw InputError(what + ": dimension '" + v.dims[d] + "' has " + std::to_string(v.shape[d]) +
                                 " points, but " + std::to_string(it->second.first) + " in variable '" +
                                 it->second.second + "'");
        }
        if (hasValues(v.values) && valueCount(v.values) != n)
            throw InputError(what + ": shape " + shapeText(v.shape) + " needs " + std::to_string(n) + " values, " +
                             std::to_string(valueCount(v.values)) + " given");
        if (v.dims.empty()) {  // GDAL lists no 0-D variable either, but opens one by name
            scalars_.push_back(&v);
            continue;
        }
        VariableInfo info;
        info.name = "/" + v.name;
        info.shortName = v.name;
        info.dimNames = v.dims;
        info.dimSizes = v.shape;
        info.numeric = hasValues(v.values);
        info.dataType = !info.numeric ? std::string("non-numeric") : !v.dataType.empty() ? v.dataType : elementType(v.values);
        info.units = textAttribute(v, "units");
        info.longName = textAttribute(v, "long_name");
        info.standardName = textAttribute(v, "standard_name");
        info.coordinates = textAttribute(v, "coordinates");
        info.bounds = textAttribute(v, "bounds");
        info.coordinate = v.dims.size() == 1 && v.dims[0] == v.name;
        variables_.push_back(std::move(info));
        arrays_.push_back(&v);
    }
    markAuxiliary(variables_);
}

const CfVariable& CfMemorySource::array(const VariableInfo& v) const {
    for (std::size_t i = 0; i < variables_.size(); ++i)
        if (variables_[i].name == v.name) return *arrays_[i];
    throw InputError(source_ + ": no variable '" + v.name + "'");
}

AxisInfo CfMemorySource::axis(const VariableInfo& variable, std::size_t dim) const {
    AxisInfo a;
    a.name = variable.dimNames.at(dim);
    checkAxisLength(source_, a.name, variable.dimSizes.at(dim));
    a.size = variable.dimSizes[dim];
    // GDAL's indexing variable: the variable named after the dimension, else the one a
    // variable's `coordinates` attribute names at the dimension's position.
    const VariableInfo* iv = nullptr;
    for (const auto& v : variables_)
        if (v.shortName == a.name && v.dimNames.size() == 1 && v.dimNames[0] == a.name) iv = &v;
    for (std::size_t i = 0; i < variables_.size() && !iv; ++i) {
        const auto names = words(variables_[i].coordinates);
        if (names.size() != variables_[i].dimNames.size()) continue;
        for (std::size_t d = 0; d < names.size() && !iv; ++d)
            if (variables_[i].dimNames[d] == a.name)
                for (const auto& v : variables_)
                    if (v.shortName == names[d]) iv = &v;
    }
    if (iv) guessGdalType(array(*iv), a);
    if (!iv || iv->dimNames.size() != 1 || !iv->numeric) iv = auxiliaryCoordinate(variables_, variable, a.name);
    if (!iv) return a;
    const CfVariable& c = array(*iv);
    a.coordinateVariable = iv->shortName;
    a.units = iv->units;
    a.positive = textAttribute(c, "positive");
    a.standardName = iv->standardName;
    a.axis = textAttribute(c, "axis");
    a.longName = iv->longName;
    a.calendar = textAttribute(c, "calendar");
    a.bounds = iv->bounds;
    a.values = read(*iv, {0}, {a.size});
    if (classifyAxis(a).role != AxisRole::Time)
        for (std::size_t n = 0; n < a.values.size(); ++n)
            if (!std::isfinite(a.values[n]))
                throw InputError(source_ + ": coordinate variable '" + iv->shortName + "' of dimension '" + a.name +
                                 "' holds a non-finite value (" + num(a.values[n]) + " at index " + std::to_string(n) +
                                 ")");
    return a;
}

std::string CfMemorySource::attributeText(const VariableInfo& variable, const char* name) const {
    const CfAttribute* a = attribute(array(variable), name);
    if (!a) return {};
    if (const auto* s = std::get_if<std::string>(&a->value)) return *s;
    std::string out;
    for (double v : std::get<std::vector<double>>(a->value)) {
        if (!out.empty()) out += ' ';
        out += num(v);
    }
    return out;
}

SampleRules CfMemorySource::rules(const VariableInfo& variable) const {
    const CfVariable& v = array(variable);
    SampleAttributes s;
    s.missingValue = numberAttribute(v, "missing_value");
    s.fillValue = numberAttribute(v, "_FillValue");
    if (s.fillValue.size() == 1) s.noData = s.fillValue[0];
    else if (s.fillValue.empty()) s.noData = singleMissingValue(v);
    s.validRange = numberAttribute(v, "valid_range");
    s.validMin = numberAttribute(v, "valid_min");
    s.validMax = numberAttribute(v, "valid_max");
    auto scale = numberAttribute(v, "scale_factor"), offset = numberAttribute(v, "add_offset");
    if (!scale.empty()) s.scale = scale[0];
    if (!offset.empty()) s.offset = offset[0];
    return sampleRules(s, variable.dataType);
}

std::vector<double> CfMemorySource::read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                                         const std::vector<std::size_t>& count) const {
    const CfVariable& v = array(variable);
    if (!hasValues(v.values)) throw FileError(source_ + ": cannot read variable '" + v.name + "': it has no numeric values");
    if (start.size() != v.shape.size() || count.size() != v.shape.size())
        throw FileError(source_ + ": cannot read variable '" + v.name + "': the hyperslab has the wrong rank");
    for (std::size_t d = 0; d < v.shape.size(); ++d)
        if (start[d] > v.shape[d] || count[d] > v.shape[d] - start[d])
            throw FileError(source_ + ": cannot read variable '" + v.name + "': the hyperslab lies beyond its shape");
    std::vector<double> out(hyperslabSamples(source_, variable, count));
    std::visit(
        [&](const auto& values) {
            if constexpr (!std::is_same_v<std::decay_t<decltype(values)>, std::monostate>)
                copyHyperslab(values.data(), v.shape, start, count, out.data());
        },
        v.values);
    return out;
}

std::optional<double> CfMemorySource::scalar(const std::string& shortName) const {
    for (const CfVariable* v : scalars_) {
        if (v->name != shortName || !hasValues(v->values)) continue;
        double raw = 0.0;
        std::visit(
            [&](const auto& values) {
                if constexpr (!std::is_same_v<std::decay_t<decltype(values)>, std::monostate>) raw = double(values[0]);
            },
            v->values);
        VariableInfo info;
        info.dataType = !v->dataType.empty() ? v->dataType : elementType(v->values);
        SampleAttributes s;
        s.missingValue = numberAttribute(*v, "missing_value");
        s.fillValue = numberAttribute(*v, "_FillValue");
        auto scale = numberAttribute(*v, "scale_factor"), offset = numberAttribute(*v, "add_offset");
        if (!scale.empty()) s.scale = scale[0];
        if (!offset.empty()) s.offset = offset[0];
        SampleRules r = sampleRules(s, info.dataType);
        if (!r.isValid(raw)) return std::nullopt;
        return raw * r.scale + r.offset;
    }
    return std::nullopt;
}

}  // namespace octrace::io::detail

#pragma once
// A NetCDF file's arrays and attributes as an octrace::io::CfDataset, read with GDAL: the
// in-memory twin of a file, for tests (tests/io/CfDatasetTest.cpp) and the fuzz target
// tests/fuzz/fuzz_netcdf_cf.cpp that compare the two paths of the CF interpretation.
#include "octrace/io/CfDataset.h"

#include <gdal_priv.h>

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <limits>
#include <list>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace octrace::test {

/// A dataset whose spans borrow buffers owned here (float and int16 arrays, as NumPy would hand
/// them over); other types are converted to owned doubles with their GDAL type name kept.
struct CfArrays {
    std::list<std::vector<float>> f32;
    std::list<std::vector<std::int16_t>> i16;
    io::CfDataset data;
};

/// Every array of `path`'s root group with its attributes (text as text, numbers as numbers):
/// what the file holds, nothing of GDAL's interpretation (raw, undecoded values, as a caller
/// hands over arrays it has not unpacked). Arrays of more than `maxSamples` are left out.
/// Throws std::runtime_error when GDAL cannot open or read the file.
inline std::unique_ptr<CfArrays> cfDatasetFromGdal(const std::string& path, const std::string& description,
                                                   std::size_t maxSamples = std::numeric_limits<std::size_t>::max()) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_MULTIDIM_RASTER | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error("GDAL cannot open " + path);
    auto out = std::make_unique<CfArrays>();
    out->data.description = description;
    auto root = ds->GetRootGroup();
    if (!root) throw std::runtime_error("GDAL gives no root group for " + path);
    // GDAL lists no 0-D variable; those a formula_terms attribute names (ROMS's hc) are added,
    // as a caller hands over the terms with the field.
    std::vector<std::string> names = root->GetMDArrayNames();
    for (const auto& name : root->GetMDArrayNames()) {
        auto a = root->OpenMDArray(name);
        auto ft = a ? a->GetAttribute("formula_terms") : nullptr;
        if (!ft || ft->GetDataType().GetClass() != GEDTC_STRING || !ft->ReadAsString()) continue;
        std::istringstream words(ft->ReadAsString());
        for (std::string w; words >> w;) {
            if (w.find(':') != std::string::npos) continue;
            auto t = root->OpenMDArray(w);
            if (t && t->GetDimensionCount() == 0 && std::find(names.begin(), names.end(), w) == names.end())
                names.push_back(w);
        }
    }
    for (const auto& name : names) {
        auto a = root->OpenMDArray(name);
        if (!a) throw std::runtime_error("GDAL cannot open the array " + name + " of " + path);  // a damaged file
        io::CfVariable v;
        v.name = a->GetName();
        std::size_t n = 1;
        bool tooMany = false;  // the product would overflow: never read
        for (const auto& d : a->GetDimensions()) {
            if (!d) throw std::runtime_error("GDAL gives a null dimension of " + name);
            v.dims.push_back(d->GetName());
            const std::size_t size = std::size_t(d->GetSize());
            v.shape.push_back(size);
            if (size != 0 && n > std::numeric_limits<std::size_t>::max() / size) tooMany = true;
            else n *= size;
        }
        // GetAttributes() leaves out those GDAL shows otherwise (units, _FillValue, packing).
        auto attributes = a->GetAttributes();
        for (const char* hidden : {"units", "_FillValue", "missing_value", "scale_factor", "add_offset"})
            if (auto attr = a->GetAttribute(hidden)) attributes.push_back(attr);
        for (const auto& attr : attributes) {
            if (attr->GetDataType().GetClass() == GEDTC_STRING) v.attributes[attr->GetName()] = attr->ReadAsString();
            else if (attr->GetDataType().GetClass() == GEDTC_NUMERIC) v.attributes[attr->GetName()] = attr->ReadAsDoubleArray();
        }
        if (tooMany || n > maxSamples) continue;
        std::vector<GUInt64> start(v.shape.size(), 0);
        const GDALDataType type = a->GetDataType().GetNumericDataType();
        auto readAs = [&](auto& buffer, GDALDataType as) {
            buffer.resize(n);
            if (!a->Read(start.data(), v.shape.data(), nullptr, nullptr, GDALExtendedDataType::Create(as), buffer.data()))
                throw std::runtime_error("cannot read " + v.name);
        };
        if (type == GDT_Float32) {
            readAs(out->f32.emplace_back(), GDT_Float32);
            v.values = std::span<const float>(out->f32.back());
        } else if (type == GDT_Int16) {
            readAs(out->i16.emplace_back(), GDT_Int16);
            v.values = std::span<const std::int16_t>(out->i16.back());
        } else {
            std::vector<double> owned;
            readAs(owned, GDT_Float64);
            v.values = std::move(owned);
            v.dataType = GDALGetDataTypeName(type);
        }
        out->data.variables.push_back(std::move(v));
    }
    return out;
}

}  // namespace octrace::test

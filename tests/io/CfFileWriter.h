#pragma once
// Writes small CF NetCDF files for tests through GDAL's multidimensional API (the netCDF
// driver), so that each test states the attributes it reads back.
#include <gdal_priv.h>

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace octrace::test {

class CfFileWriter {
public:
    /// `netcdf4`: NetCDF-4 (HDF5) instead of NetCDF-3 classic.
    explicit CfFileWriter(const std::string& path, bool netcdf4 = false) {
        GDALAllRegister();
        GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
        if (!driver) throw std::runtime_error("GDAL has no netCDF driver");
        CPLStringList options;
        options.SetNameValue("FORMAT", netcdf4 ? "NC4" : "NC");
        ds_.reset(driver->CreateMultiDimensional(path.c_str(), nullptr, options.List()));
        if (!ds_) throw std::runtime_error("GDAL cannot create " + path);
        root_ = ds_->GetRootGroup();
    }

    std::shared_ptr<GDALDimension> dimension(const std::string& name, std::size_t size) {
        auto d = root_->CreateDimension(name, "", "", size);
        if (!d) throw std::runtime_error("cannot create dimension " + name);
        dims_[name] = d;
        return d;
    }

    /// A 1-D coordinate variable named after its dimension (created here), with text attributes.
    std::shared_ptr<GDALMDArray> coordinate(const std::string& name, const std::vector<double>& values,
                                            const std::map<std::string, std::string>& attributes) {
        dimension(name, values.size());
        return variable(name, {name}, GDT_Float64, values, attributes);
    }

    /// A variable over existing dimensions, written from `values` (C order) converted to `type`.
    std::shared_ptr<GDALMDArray> variable(const std::string& name, const std::vector<std::string>& dims, GDALDataType type,
                                          const std::vector<double>& values,
                                          const std::map<std::string, std::string>& attributes = {}) {
        std::vector<std::shared_ptr<GDALDimension>> ds;
        for (const auto& d : dims) ds.push_back(dims_.at(d));
        auto a = root_->CreateMDArray(name, ds, GDALExtendedDataType::Create(type));
        if (!a) throw std::runtime_error("cannot create variable " + name);
        for (const auto& [k, v] : attributes) text(*a, k, v);
        std::vector<GUInt64> start(ds.size(), 0);
        std::vector<size_t> count;
        std::size_t n = 1;
        for (const auto& d : ds) {
            count.push_back(size_t(d->GetSize()));
            n *= size_t(d->GetSize());
        }
        if (n != values.size()) throw std::runtime_error("wrong number of values for " + name);
        if (!a->Write(start.data(), count.data(), nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64),
                      values.data()))
            throw std::runtime_error("cannot write variable " + name);
        return a;
    }

    static void text(GDALMDArray& a, const std::string& name, const std::string& value) {
        auto attr = a.CreateAttribute(name, {}, GDALExtendedDataType::CreateString());
        if (!attr || !attr->Write(value.c_str())) throw std::runtime_error("cannot write attribute " + name);
    }

    /// A numeric attribute of `type` (e.g. the variable's own type for missing_value, valid_range).
    static void numbers(GDALMDArray& a, const std::string& name, GDALDataType type, const std::vector<double>& values) {
        auto attr = a.CreateAttribute(name, {GUInt64(values.size())}, GDALExtendedDataType::Create(type));
        if (!attr || !attr->Write(values.data(), values.size())) throw std::runtime_error("cannot write attribute " + name);
    }

    /// Closes the file (the destructor does too).
    void close() {
        root_.reset();
        ds_.reset();
    }
    ~CfFileWriter() { close(); }

private:
    GDALDatasetUniquePtr ds_;
    std::shared_ptr<GDALGroup> root_;
    std::map<std::string, std::shared_ptr<GDALDimension>> dims_;
};

}  // namespace octrace::test

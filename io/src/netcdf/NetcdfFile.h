#pragma once
// An open NetCDF file seen through GDAL's multidimensional API (internal). GDAL types stay in
// NetcdfFile.cpp; this header speaks std types only.
#include "netcdf/GeoAxis.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace octrace::io::detail {

struct VariableInfo {
    std::string name;        ///< full name ("/TEMP", "/group/var")
    std::string shortName;   ///< "TEMP"
    std::vector<std::string> dimNames;
    std::vector<std::size_t> dimSizes;
    std::string dataType;    ///< "Float32", ...
    std::string units, longName;
    std::string standardName;  ///< CF standard_name, may be empty
    std::string coordinates;   ///< CF `coordinates` attribute: names of auxiliary coordinate variables
    std::string bounds;        ///< CF `bounds` attribute: name of the cell-boundary variable
    bool numeric = false;
    bool coordinate = false; ///< 1-D variable named after its own dimension
    bool auxiliary = false;  ///< named by another variable's `coordinates` or `bounds` attribute

    /// Dimensions with more than one sample.
    int extent() const;
    /// "TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR)"
    std::string signature() const;
};

/// How raw samples become values: missing markers, valid range, packing.
struct SampleRules {
    std::vector<double> missing;  ///< missing_value, _FillValue (or the NetCDF default fill)
    double validMin = -std::numeric_limits<double>::infinity();
    double validMax = std::numeric_limits<double>::infinity();
    double scale = 1.0, offset = 0.0;
    bool isValid(double raw) const;
};

class NetcdfFile {
public:
    /// Opens `path` with GDAL's netCDF driver. Throws FileError with GDAL's message.
    explicit NetcdfFile(const std::string& path);
    ~NetcdfFile();
    NetcdfFile(const NetcdfFile&) = delete;
    NetcdfFile& operator=(const NetcdfFile&) = delete;

    /// Every array of every group.
    const std::vector<VariableInfo>& variables() const;
    /// Dimension `dim` of `variable` and its coordinate variable: the 1-D variable named after
    /// the dimension, else a 1-D variable over that dimension named in `variable`'s CF
    /// `coordinates` attribute (an auxiliary coordinate variable).
    AxisInfo axis(const VariableInfo& variable, std::size_t dim) const;
    /// Attribute `name` of `variable` as text ("-32767", "0.01 0.5", a string); empty if absent.
    std::string attributeText(const VariableInfo& variable, const char* name) const;
    SampleRules rules(const VariableInfo& variable) const;
    /// A hyperslab as double, C order over the variable's dimensions. Throws FileError.
    std::vector<double> read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                             const std::vector<std::size_t>& count) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace octrace::io::detail

#pragma once
// An open NetCDF file, or Zarr store, seen through GDAL's multidimensional API (internal): the
// file source of the CF interpretation (CfSource.h). Both drivers hand over the same arrays,
// dimensions and attributes, so one source serves both. GDAL types stay in NetcdfFile.cpp; this
// header speaks std types only.
#include "netcdf/CfSource.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// The GDAL driver that opens a NetcdfFile's path.
enum class GdalDriver { NetCdf, Zarr };

/// "netCDF" or "Zarr", as GDAL names the driver (and octrace's messages say it).
const char* gdalDriverName(GdalDriver driver);

class NetcdfFile final : public CfSource {
public:
    /// Opens `path` with GDAL's netCDF driver, or with its Zarr driver (a store's folder).
    /// Throws FileError with GDAL's message.
    explicit NetcdfFile(const std::string& path, GdalDriver driver = GdalDriver::NetCdf);
    ~NetcdfFile() override;
    NetcdfFile(const NetcdfFile&) = delete;
    NetcdfFile& operator=(const NetcdfFile&) = delete;

    /// Every array of every group (GDAL lists no 0-D ones).
    const std::vector<VariableInfo>& variables() const override;
    /// The coordinate variable is GDAL's indexing variable of the dimension when it is 1-D and
    /// numeric, else the auxiliary one (CfSource::axis); the dimension's type and direction are
    /// GDAL's guess.
    AxisInfo axis(const VariableInfo& variable, std::size_t dim) const override;
    std::string attributeText(const VariableInfo& variable, const char* name) const override;
    /// The no-data value is GDAL's (_FillValue, else a single missing_value; a Zarr array's
    /// `fill_value`, which xarray writes from _FillValue).
    SampleRules rules(const VariableInfo& variable) const override;
    /// Throws FileError naming the variable when GDAL fails, also when it reports a failure
    /// (a Zarr chunk that does not decompress) but returns the samples all the same.
    std::vector<double> read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                             const std::vector<std::size_t>& count) const override;
    /// A 0-D variable of the root group, opened by name (GDAL lists none).
    std::optional<double> scalar(const std::string& shortName) const override;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace octrace::io::detail

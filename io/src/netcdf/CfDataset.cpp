#include "octrace/io/CfDataset.h"

#include "netcdf/CfMemorySource.h"
#include "netcdf/NetcdfInterpretation.h"

namespace octrace::io {

ScalarField readCfDataset(const CfDataset& data, const FieldRequest& req) {
    const std::string source = detail::cfSourceName(data);
    detail::checkFieldRequest(source, req);
    detail::CfMemorySource memory(data);
    return detail::interpretCf(source, memory, req);
}

std::string describeCfDataset(const CfDataset& data, const FieldRequest& req) {
    const std::string source = detail::cfSourceName(data);
    if (req.hasRegion) checkRegion(req.region, source);
    detail::CfMemorySource memory(data);
    return detail::describeCf(source, "format: in-memory arrays (" + std::to_string(data.variables.size()) +
                                          " variables), read by NetCDF's CF rules",
                              memory, req);
}

std::vector<std::string> cfVolumeVariables(const CfDataset& data) {
    return detail::cfVolumeNames(detail::CfMemorySource(data));
}

}  // namespace octrace::io

#pragma once
// The in-memory source of the CF interpretation (internal): a CfDataset's arrays seen as a
// NetCDF file is seen through GDAL (NetcdfFile), so that both give the same field. Where GDAL
// adds something of its own (the no-data value, its guess of a dimension's type and direction,
// its choice of a dimension's indexing variable), it is reproduced here from the attributes.
#include "netcdf/CfSource.h"

#include "octrace/io/CfDataset.h"

#include <string>
#include <vector>

namespace octrace::io::detail {

class CfMemorySource final : public CfSource {
public:
    /// Checks `data` and lists its variables (0-D ones left out, as GDAL does). Borrows `data`,
    /// which must outlive this object. @throws InputError naming `data.description` and the
    /// variable: a shape that disagrees with the dimension names or the number of values, a
    /// dimension with two sizes, an unnamed or repeated variable.
    explicit CfMemorySource(const CfDataset& data);

    /// `data.description`, or "in-memory dataset".
    const std::string& source() const { return source_; }

    const std::vector<VariableInfo>& variables() const override { return variables_; }
    /// Also throws InputError when a coordinate variable of a non-time axis holds a non-finite value.
    AxisInfo axis(const VariableInfo& variable, std::size_t dim) const override;
    std::string attributeText(const VariableInfo& variable, const char* name) const override;
    SampleRules rules(const VariableInfo& variable) const override;
    std::vector<double> read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                             const std::vector<std::size_t>& count) const override;
    /// A 0-D variable of the dataset (checked, not listed).
    std::optional<double> scalar(const std::string& shortName) const override;

private:
    const CfVariable& array(const VariableInfo& v) const;

    std::string source_;
    std::vector<VariableInfo> variables_;
    std::vector<const CfVariable*> arrays_;  // parallel to variables_, into the borrowed CfDataset
    std::vector<const CfVariable*> scalars_;  // the 0-D variables, into the borrowed CfDataset
};

/// `data.description`, or "in-memory dataset" when it is empty.
std::string cfSourceName(const CfDataset& data);

}  // namespace octrace::io::detail

#pragma once
// What the CF interpretation reads a dataset through (internal, std types only): its variables,
// the coordinate variable of each dimension, attributes, masking and packing rules, and
// hyperslabs. Two sources implement it: NetcdfFile (a file, through GDAL's netCDF driver) and
// CfMemorySource (arrays handed over in memory as an octrace::io::CfDataset, e.g. an xarray
// DataArray from Python). NetcdfReader, NetcdfLayout and SoundSpeedField see only this
// interface, so both sources get one interpretation.
#include "netcdf/GeoAxis.h"

#include <cstdint>
#include <limits>
#include <optional>
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

/// The attributes SampleRules come from, as a source finds them.
struct SampleAttributes {
    std::vector<double> missingValue, fillValue;  ///< numeric missing_value, _FillValue
    std::optional<double> noData;                 ///< GDAL's no-data value: _FillValue, else a single missing_value
    std::vector<double> validRange, validMin, validMax;
    std::optional<double> scale, offset;          ///< scale_factor, add_offset
};

/// The rules of a variable of `dataType` ("Int16", ...) with attributes `a`: every
/// missing_value and _FillValue, the no-data value, and NetCDF's default fill for the type when
/// the variable has neither a no-data value nor a _FillValue.
SampleRules sampleRules(const SampleAttributes& a, const std::string& dataType);

/// Marks the variables another variable names in its `coordinates` or `bounds` attribute.
void markAuxiliary(std::vector<VariableInfo>& vars);

/// The auxiliary coordinate variable of dimension `dim` of `variable`: a numeric 1-D variable
/// over that dimension named in `variable`'s CF `coordinates` attribute; null if none.
const VariableInfo* auxiliaryCoordinate(const std::vector<VariableInfo>& vars, const VariableInfo& variable,
                                        const std::string& dim);

/// Refuses a dimension longer than kMaxAxisPoints (FileError naming `source` and the dimension).
void checkAxisLength(const std::string& source, const std::string& dim, std::uint64_t size);

/// The number of samples of a hyperslab of `count`; refuses (FileError naming `source` and the
/// variable) one too large to read into doubles.
std::uint64_t hyperslabSamples(const std::string& source, const VariableInfo& variable,
                               const std::vector<std::size_t>& count);

class CfSource {
public:
    virtual ~CfSource() = default;

    /// Every variable (of every group).
    virtual const std::vector<VariableInfo>& variables() const = 0;
    /// Dimension `dim` of `variable` and its coordinate variable: the 1-D variable named after
    /// the dimension, else a 1-D variable over that dimension named in `variable`'s CF
    /// `coordinates` attribute (an auxiliary coordinate variable). Throws FileError (an axis
    /// longer than kMaxAxisPoints, an unreadable coordinate variable) or InputError.
    virtual AxisInfo axis(const VariableInfo& variable, std::size_t dim) const = 0;
    /// Attribute `name` of `variable` as text ("-32767", "0.01 0.5", a string); empty if absent.
    virtual std::string attributeText(const VariableInfo& variable, const char* name) const = 0;
    virtual SampleRules rules(const VariableInfo& variable) const = 0;
    /// A hyperslab as double, C order over the variable's dimensions. Throws FileError.
    virtual std::vector<double> read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                                     const std::vector<std::size_t>& count) const = 0;
    /// The value of the 0-D numeric variable `shortName` (e.g. ROMS's `hc`, named by a
    /// `formula_terms` attribute), unpacked; nullopt when there is none or its raw value is
    /// missing or invalid. 0-D variables are not in variables(). Throws FileError.
    virtual std::optional<double> scalar(const std::string& shortName) const = 0;

protected:
    CfSource() = default;
    CfSource(const CfSource&) = default;
    CfSource& operator=(const CfSource&) = default;
};

}  // namespace octrace::io::detail

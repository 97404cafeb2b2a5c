#pragma once
/// @file CfDataset.h
/// CF-convention arrays handed over in memory (e.g. an xarray DataArray's values, coordinates
/// and attributes from Python) and read by the same CF interpretation as NetCDF files
/// (NetcdfReader): for the same arrays and attributes and the same FieldRequest, readCfDataset
/// gives the ScalarField NetcdfReader::read gives for a file holding them, except for
/// ScalarField::source, which is the dataset's description instead of the file's path.
/// Plain std types only: no GDAL, no Python.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace octrace::io {

/// One attribute of a variable: text, or numbers (a scalar is one number). Numbers are read
/// where a file's numeric attributes are (_FillValue, missing_value, valid_range, valid_min,
/// valid_max, scale_factor, add_offset), text where its text attributes are (units,
/// standard_name, long_name, positive, calendar, axis, coordinates, bounds).
struct CfAttribute {
    std::variant<std::string, std::vector<double>> value;

    CfAttribute() = default;
    CfAttribute(std::string text) : value(std::move(text)) {}               // NOLINT: implicit by design
    CfAttribute(const char* text) : value(std::string(text)) {}             // NOLINT
    CfAttribute(double number) : value(std::vector<double>{number}) {}      // NOLINT
    CfAttribute(std::vector<double> numbers) : value(std::move(numbers)) {}  // NOLINT
};

/// The samples of a variable in C order over its dimensions: borrowed (a span over memory the
/// caller keeps alive and unchanged during the call, in the array's own element type, e.g. a
/// NumPy buffer) or owned doubles. std::monostate: no numeric values (e.g. a text variable),
/// listed but never read.
using CfValues =
    std::variant<std::monostate, std::span<const float>, std::span<const double>, std::span<const std::int8_t>,
                 std::span<const std::uint8_t>, std::span<const std::int16_t>, std::span<const std::uint16_t>,
                 std::span<const std::int32_t>, std::span<const std::uint32_t>, std::span<const std::int64_t>,
                 std::span<const std::uint64_t>, std::vector<double>>;

/// One variable, as in a NetCDF file. A coordinate variable is a 1-D variable named after its
/// dimension (e.g. "lon" over "lon"); time coordinates are the encoded numbers with their
/// `units` ("days since 1900-01-01") and `calendar` attributes. Values are read raw, as a file
/// stores them: missing_value / _FillValue / valid_* are compared with them, then scale_factor
/// and add_offset applied (values already unpacked, with NaN for missing, simply come without
/// those attributes). A 0-D variable (a scalar coordinate) is checked but not listed, as GDAL
/// lists none in a file.
struct CfVariable {
    std::string name;                   ///< short name, e.g. "TEMP"; unique in the dataset
    std::vector<std::string> dims;      ///< dimension names, C order (slowest first)
    std::vector<std::size_t> shape;     ///< one size per dimension
    /// The stored type as GDAL names it ("Float32", "Float64", "Int16", "UInt16", "Int32",
    /// "UInt32", "Byte", ...): shown by describe and choosing NetCDF's default fill value for a
    /// variable without _FillValue. Empty: the element type of `values` (owned: "Float64").
    /// Set it when the values were converted (e.g. int16 handed over as doubles).
    std::string dataType;
    CfValues values;
    std::map<std::string, CfAttribute> attributes;
};

struct CfDataset {
    std::vector<CfVariable> variables;
    /// The dataset's global attributes; like a file's, not read by the interpretation today.
    std::map<std::string, CfAttribute> attributes;
    /// Names the data in messages and in ScalarField::source (where a file's path would be),
    /// e.g. "xarray DataArray TEMP"; empty: "in-memory dataset".
    std::string description;
};

/// The field `req` asks for, as NetcdfReader::read gives it for a file holding `data`'s
/// variables (variable choice, axis roles, geographic mapping, region across the dateline,
/// depth range, time step by index or by date in the axis's calendar, masking and unpacking,
/// sound speed derived from temperature and salinity, notes and warnings), with messages
/// naming `data.description` instead of a path.
/// @throws InputError when `data` is inconsistent, naming the variable: a shape that disagrees
///         with its dimension names or with the number of values, a dimension with two sizes
///         (e.g. a coordinate variable of the wrong length), non-finite values in a coordinate
///         variable of a non-time axis, two variables of one name; otherwise as
///         NetcdfReader::read (UsageError, InputError, FileError, EmptyResultError, and
///         LimitError before anything the size of the field is allocated when the samples
///         would need more than `req.memoryBudget` bytes).
/// Borrows `data` for the call only; the result owns its samples. Thread-safe (no shared state).
ScalarField readCfDataset(const CfDataset& data, const FieldRequest& req);

/// The text NetcdfReader::describe gives for a file holding `data`'s variables (dimensions and
/// their roles, variables with their valid range, the grid `req` asks for), headed by
/// `data.description` and "format: in-memory arrays". Throws as readCfDataset.
std::string describeCfDataset(const CfDataset& data, const FieldRequest& req = {});

/// The short names of the variables with at least 3 dimensions longer than 1 (the volumes
/// readCfDataset reads without `req.variable`), in `data`'s order. Throws InputError when
/// `data` is inconsistent.
std::vector<std::string> cfVolumeVariables(const CfDataset& data);

}  // namespace octrace::io

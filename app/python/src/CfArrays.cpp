// xarray's arrays into the NetCDF reader's CF interpretation (io/CfDataset.h): the accessor
// (app/python/octrace/_xarray.py) hands over each variable's name, dimensions, values (NumPy,
// borrowed for the call) and attributes; the C++ reads them exactly as it reads a file.
#include "Module.h"

#include "octrace/io/CfDataset.h"
#include "octrace/model/OptionTable.h"
#include "octrace/util/Error.h"

#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <span>
#include <string>

namespace octrace::python {
namespace {

using Array = nb::ndarray<nb::ro, nb::c_contig, nb::device::cpu>;

/// The values of `array` as a span of its own element type (borrowed: the caller keeps the array).
io::CfValues borrowed(const Array& a, const std::string& name) {
    const std::size_t n = a.size();
    const auto span = [&](auto* p) { return std::span(p, n); };
    const nb::dlpack::dtype t = a.dtype();
    if (t == nb::dtype<float>()) return span(static_cast<const float*>(a.data()));
    if (t == nb::dtype<double>()) return span(static_cast<const double*>(a.data()));
    if (t == nb::dtype<std::int8_t>()) return span(static_cast<const std::int8_t*>(a.data()));
    if (t == nb::dtype<std::uint8_t>()) return span(static_cast<const std::uint8_t*>(a.data()));
    if (t == nb::dtype<std::int16_t>()) return span(static_cast<const std::int16_t*>(a.data()));
    if (t == nb::dtype<std::uint16_t>()) return span(static_cast<const std::uint16_t*>(a.data()));
    if (t == nb::dtype<std::int32_t>()) return span(static_cast<const std::int32_t*>(a.data()));
    if (t == nb::dtype<std::uint32_t>()) return span(static_cast<const std::uint32_t*>(a.data()));
    if (t == nb::dtype<std::int64_t>()) return span(static_cast<const std::int64_t*>(a.data()));
    if (t == nb::dtype<std::uint64_t>()) return span(static_cast<const std::uint64_t*>(a.data()));
    throw UsageError(name + ": values of an unsupported type (give numbers)");
}

/// A dict {name, dims, shape, values (an array or None), attributes {name: str | list of float}}
/// as a CfVariable.
io::CfVariable variable(const nb::dict& d) {
    io::CfVariable v;
    v.name = nb::cast<std::string>(d["name"]);
    v.dims = nb::cast<std::vector<std::string>>(d["dims"]);
    v.shape = nb::cast<std::vector<std::size_t>>(d["shape"]);
    if (!d["values"].is_none()) v.values = borrowed(nb::cast<Array>(d["values"]), v.name);
    if (d.contains("data_type")) v.dataType = nb::cast<std::string>(d["data_type"]);
    for (const auto& [key, value] : nb::cast<nb::dict>(d["attributes"])) {
        const std::string k = nb::cast<std::string>(key);
        if (nb::isinstance<nb::str>(value)) v.attributes[k] = io::CfAttribute(nb::cast<std::string>(value));
        else v.attributes[k] = io::CfAttribute(nb::cast<std::vector<double>>(value));
    }
    return v;
}

io::CfDataset dataset(const nb::list& variables, const std::string& description) {
    io::CfDataset data;
    data.description = description;
    for (nb::handle h : variables) data.variables.push_back(variable(nb::cast<nb::dict>(h)));
    return data;
}

}  // namespace

void bindCfArrays(nb::module_& m) {
    m.def("read_cf", [](const nb::list& variables, const std::string& description, const Settings& settings, bool planar) {
        const io::CfDataset data = dataset(variables, description);  // borrows the arrays `variables` holds
        io::FieldRequest req = readerRequest(settings);
        req.acceptPlanar = planar;
        // A curvilinear grid is resampled as octrace.open does (model::loadField): at the default depth.
        req.horizontalSamples = io::latticeSamplesForDepth(int(model::opt::depth.defaultValue));
        return makeField(runInterruptible([&] { return io::readCfDataset(data, req); }), description);
    }, "variables"_a, "description"_a, "settings"_a, "planar"_a = false,
          "The field the NetCDF reader's CF interpretation reads from these variables (io/CfDataset.h); `planar`: "
          "a 2-D field is read as a map (FieldRequest::acceptPlanar), as slices read it.");
    m.def("describe_cf", [](const nb::list& variables, const std::string& description, const Settings& settings) {
        const io::CfDataset data = dataset(variables, description);
        const io::FieldRequest req = readerRequest(settings);
        return model::sayForPython(runInterruptible([&] { return io::describeCfDataset(data, req); }));
    }, "variables"_a, "description"_a, "settings"_a);
}

}  // namespace octrace::python

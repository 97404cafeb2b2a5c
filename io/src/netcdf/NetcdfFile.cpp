#include "netcdf/NetcdfFile.h"

#include "input/ChildProbe.h"
#include "octree/Crc32c.h"
#include "input/GdalSupport.h"
#include "input/InputFile.h"

#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <limits>
#include <mutex>

#include <sys/stat.h>

namespace octrace::io::detail {
namespace {

std::string stringAttribute(const GDALMDArray& a, const char* name) {
    auto attr = a.GetAttribute(name);
    if (!attr || attr->GetDataType().GetClass() != GEDTC_STRING) return {};
    const char* s = attr->ReadAsString();
    return s ? s : "";
}

std::vector<double> numberAttribute(const GDALMDArray& a, const char* name) {
    auto attr = a.GetAttribute(name);
    if (!attr || attr->GetDataType().GetClass() != GEDTC_NUMERIC) return {};
    return attr->ReadAsDoubleArray();
}

void collect(const std::string& path, const std::shared_ptr<GDALGroup>& group, std::vector<VariableInfo>& out,
             std::vector<std::shared_ptr<GDALMDArray>>& arrays) {
    for (const auto& name : group->GetMDArrayNames()) {
        auto a = group->OpenMDArray(name);
        if (!a) {  // e.g. a Zarr codec GDAL lacks: said, not silently missing from the variables
            log::warning(path + ": variable '" + name + "' left out: GDAL cannot open it: " + GdalMessages::last());
            continue;
        }
        VariableInfo v;
        v.name = a->GetFullName();
        v.shortName = a->GetName();
        for (const auto& d : a->GetDimensions()) {
            v.dimNames.push_back(d->GetName());
            v.dimSizes.push_back(std::size_t(d->GetSize()));
        }
        v.numeric = a->GetDataType().GetClass() == GEDTC_NUMERIC;
        v.dataType = v.numeric ? GDALGetDataTypeName(a->GetDataType().GetNumericDataType()) : "non-numeric";
        v.units = a->GetUnit();
        v.longName = stringAttribute(*a, "long_name");
        v.standardName = stringAttribute(*a, "standard_name");
        v.coordinates = stringAttribute(*a, "coordinates");
        v.bounds = stringAttribute(*a, "bounds");
        v.coordinate = v.dimNames.size() == 1 && v.dimNames[0] == v.shortName;
        out.push_back(v);
        arrays.push_back(a);
    }
    for (const auto& name : group->GetGroupNames())
        if (auto sub = group->OpenGroup(name)) collect(path, sub, out, arrays);
}

// Whether the file (on disk or a GDAL virtual file) starts with the HDF5 signature, i.e. is
// NetCDF-4. Only HDF5-based files are opened in a child first: classic files are walked by
// octrace's own header reader before GDAL sees them.
bool isHdf5(const std::string& path) {
    static const char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
    VSILFILE* f = VSIFOpenL(path.c_str(), "rb");
    if (!f) return false;
    char head[8] = {};
    bool yes = VSIFReadL(head, 1, 8, f) == 8 && std::memcmp(head, signature, 8) == 0;
    VSIFCloseL(f);
    return yes;
}

// What identifies a file's state for the probe: on disk its device, inode, size and
// modification time; for a GDAL in-memory file (/vsimem/, the fuzz target) its size and the
// CRC-32C of its bytes. Empty when unknown (the file is then always probed).
std::string fileIdentity(const std::string& path) {
    if (path.rfind("/vsimem/", 0) == 0) {
        vsi_l_offset length = 0;
        GByte* bytes = VSIGetMemFileBuffer(path.c_str(), &length, FALSE);
        if (!bytes) return {};
        return path + "|" + std::to_string(length) + "|" + std::to_string(crc32c(bytes, std::size_t(length)));
    }
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return {};
    return path + "|" + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + "|" + std::to_string(st.st_size) +
           "|" + std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec);
}

// Runs the metadata reading in a child first (ChildProbe.h), once per state of a file: the
// CLI and the studio open the same file several times (listing, then reading), and each probe
// costs a fork (and a refusal may have cost the whole deadline). The last few outcomes are
// remembered: an empty message for a probe that finished, the refusal otherwise.
void guardHdf5Metadata(const std::string& path, const std::function<void()>& probe) {
    static std::mutex mutex;
    static std::vector<std::pair<std::string, std::string>> outcomes;  // identity, refusal
    const std::string id = fileIdentity(path);
    {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& [known, refusal] : outcomes)
            if (!id.empty() && known == id) {
                if (refusal.empty()) return;
                throw FileError(refusal);
            }
    }
    std::string refusal;
    try {
        probeInChild(path, "the NetCDF-4 (HDF5) metadata", hdf5OpenDeadline(), probe);
    } catch (const FileError& e) {
        refusal = e.what();
    }
    if (!id.empty()) {
        std::lock_guard<std::mutex> lock(mutex);
        if (outcomes.size() >= 16) outcomes.erase(outcomes.begin());
        outcomes.emplace_back(id, refusal);
    }
    if (!refusal.empty()) throw FileError(refusal);
}

struct Opened {
    GDALDatasetUniquePtr dataset;
    std::vector<VariableInfo> variables;
    std::vector<std::shared_ptr<GDALMDArray>> arrays;
};

Opened openAndCollect(const std::string& path, GdalDriver driver) {
    GdalMessages messages;
    Opened o;
    const char* const drivers[] = {gdalDriverName(driver), nullptr};
    o.dataset.reset(GDALDataset::Open(path.c_str(), GDAL_OF_MULTIDIM_RASTER | GDAL_OF_READONLY, drivers));
    if (!o.dataset) {
        std::string detail = CPLGetLastErrorType() != CE_None ? GdalMessages::last()
                             : driver == GdalDriver::Zarr    ? std::string("its metadata are incomplete or corrupt")
                                                             : std::string("the file is truncated or corrupt");
        throw FileError(path + ": GDAL's " + gdalDriverName(driver) + " driver cannot open it: " + detail);
    }
    auto root = o.dataset->GetRootGroup();
    if (!root) throw FileError(path + ": GDAL gives no root group: " + GdalMessages::last());
    collect(path, root, o.variables, o.arrays);
    return o;
}

}  // namespace

const char* gdalDriverName(GdalDriver driver) { return driver == GdalDriver::Zarr ? "Zarr" : "netCDF"; }

struct NetcdfFile::Impl {
    std::string path;
    GdalDriver driver = GdalDriver::NetCdf;
    GDALDatasetUniquePtr dataset;
    std::vector<VariableInfo> variables;
    std::vector<std::shared_ptr<GDALMDArray>> arrays;  // parallel to variables

    const std::shared_ptr<GDALMDArray>& array(const VariableInfo& v) const {
        for (std::size_t i = 0; i < variables.size(); ++i)
            if (variables[i].name == v.name) return arrays[i];
        throw InputError(path + ": no variable '" + v.name + "'");
    }
};

NetcdfFile::NetcdfFile(const std::string& path, GdalDriver driver) : impl_(std::make_unique<Impl>()) {
    registerGdal();
    impl_->path = path;
    impl_->driver = driver;
    // HDF5 can hang on a corrupt NetCDF-4 file while its metadata are read (fuzzing.md): that
    // part runs first in a child process with a deadline.
    if (driver == GdalDriver::NetCdf && isHdf5(path)) guardHdf5Metadata(path, [&path] { openAndCollect(path, GdalDriver::NetCdf); });
    Opened o = openAndCollect(path, driver);
    impl_->dataset = std::move(o.dataset);
    impl_->variables = std::move(o.variables);
    impl_->arrays = std::move(o.arrays);
    markAuxiliary(impl_->variables);
}

NetcdfFile::~NetcdfFile() = default;

const std::vector<VariableInfo>& NetcdfFile::variables() const { return impl_->variables; }

AxisInfo NetcdfFile::axis(const VariableInfo& variable, std::size_t dim) const {
    GdalMessages messages;
    auto d = impl_->array(variable)->GetDimensions().at(dim);
    AxisInfo a;
    a.name = d->GetName();
    checkAxisLength(impl_->path, a.name, d->GetSize());
    a.size = std::size_t(d->GetSize());
    a.gdalType = d->GetType();
    a.gdalDirection = d->GetDirection();
    auto iv = d->GetIndexingVariable();
    if (!iv || iv->GetDimensionCount() != 1 || iv->GetDataType().GetClass() != GEDTC_NUMERIC) {
        iv.reset();
        if (const VariableInfo* c = auxiliaryCoordinate(impl_->variables, variable, a.name)) iv = impl_->array(*c);
    }
    if (!iv) return a;
    a.coordinateVariable = iv->GetName();
    a.units = iv->GetUnit();
    a.positive = stringAttribute(*iv, "positive");
    a.standardName = stringAttribute(*iv, "standard_name");
    a.axis = stringAttribute(*iv, "axis");
    a.longName = stringAttribute(*iv, "long_name");
    a.calendar = stringAttribute(*iv, "calendar");
    a.bounds = stringAttribute(*iv, "bounds");
    std::vector<double> values(a.size);
    GUInt64 start = 0;
    std::size_t count = a.size;
    const bool read = iv->Read(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data());
    if (!read || (impl_->driver == GdalDriver::Zarr && CPLGetLastErrorType() >= CE_Failure))  // as in read()
        throw FileError(impl_->path + ": cannot read coordinate variable '" + iv->GetName() + "': " + GdalMessages::last());
    a.values = std::move(values);
    return a;
}

SampleRules NetcdfFile::rules(const VariableInfo& variable) const {
    GdalMessages messages;
    const auto& a = *impl_->array(variable);
    SampleAttributes s;
    s.missingValue = numberAttribute(a, "missing_value");
    s.fillValue = numberAttribute(a, "_FillValue");
    bool has = false;
    double noData = a.GetNoDataValueAsDouble(&has);
    if (has) s.noData = noData;
    s.validRange = numberAttribute(a, "valid_range");
    s.validMin = numberAttribute(a, "valid_min");
    s.validMax = numberAttribute(a, "valid_max");
    double scale = a.GetScale(&has);
    if (has) s.scale = scale;
    double offset = a.GetOffset(&has);
    if (has) s.offset = offset;
    return sampleRules(s, variable.dataType);
}

std::string NetcdfFile::attributeText(const VariableInfo& variable, const char* name) const {
    GdalMessages messages;
    auto attr = impl_->array(variable)->GetAttribute(name);
    if (!attr) return {};
    if (attr->GetDataType().GetClass() == GEDTC_STRING) {
        const char* s = attr->ReadAsString();
        return s ? s : "";
    }
    if (attr->GetDataType().GetClass() != GEDTC_NUMERIC) return {};
    std::string out;
    for (double v : attr->ReadAsDoubleArray()) {
        if (!out.empty()) out += ' ';
        out += num(v);
    }
    return out;
}

std::vector<double> NetcdfFile::read(const VariableInfo& variable, const std::vector<std::uint64_t>& start,
                                     const std::vector<std::size_t>& count) const {
    GdalMessages messages;
    std::vector<double> buffer(hyperslabSamples(impl_->path, variable, count));
    std::vector<GUInt64> gstart(start.begin(), start.end());
    // GDAL's Zarr driver reports a chunk that does not decompress as an error but may return
    // true with the chunk left as it was: for a store, a failure reported during the read
    // counts as one.
    const bool read = impl_->array(variable)->Read(gstart.data(), count.data(), nullptr, nullptr,
                                                   GDALExtendedDataType::Create(GDT_Float64), buffer.data());
    if (!read || (impl_->driver == GdalDriver::Zarr && CPLGetLastErrorType() >= CE_Failure))
        throw FileError(impl_->path + ": cannot read variable '" + variable.shortName + "'" +
                        (impl_->driver == GdalDriver::Zarr ? " of the Zarr store" : "") + ": " + GdalMessages::last());
    return buffer;
}

std::optional<double> NetcdfFile::scalar(const std::string& shortName) const {
    GdalMessages messages;
    auto root = impl_->dataset->GetRootGroup();
    auto a = root ? root->OpenMDArray(shortName) : nullptr;
    if (!a || a->GetDimensionCount() != 0 || a->GetDataType().GetClass() != GEDTC_NUMERIC) return std::nullopt;
    double raw = 0.0;
    if (!a->Read(nullptr, nullptr, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), &raw))
        throw FileError(impl_->path + ": cannot read variable '" + shortName + "': " + GdalMessages::last());
    SampleAttributes s;
    s.missingValue = numberAttribute(*a, "missing_value");
    s.fillValue = numberAttribute(*a, "_FillValue");
    bool has = false;
    double scale = a->GetScale(&has);
    if (has) s.scale = scale;
    double offset = a->GetOffset(&has);
    if (has) s.offset = offset;
    SampleRules r = sampleRules(s, GDALGetDataTypeName(a->GetDataType().GetNumericDataType()));
    if (!r.isValid(raw)) return std::nullopt;
    return raw * r.scale + r.offset;
}

}  // namespace octrace::io::detail

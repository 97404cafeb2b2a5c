#include "octrace/io/FieldReader.h"

#include "FormatSniffer.h"
#include "InputFile.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/io/NrrdReader.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <filesystem>

namespace octrace::io {
namespace {

using detail::FileKind;

const char* kSupported = "supported: NetCDF (.nc, .cdf, .nc4: classic, 64-bit offset, CDF-5, NetCDF-4/HDF5), "
                         "NRRD (.nrrd, .nhdr)";

FileKind kindOf(const std::string& path) {
    detail::Sniffed s = detail::sniffFormat(path);
    if (s.kind != FileKind::Unknown) return s.kind;
    // No known signature: trust the extension so the format's reader can say what is wrong.
    std::string ext = detail::lower(std::filesystem::path(path).extension().string());
    if (ext == ".nrrd" || ext == ".nhdr") return FileKind::Nrrd;
    if (ext == ".nc" || ext == ".cdf" || ext == ".nc4" || ext == ".netcdf") return FileKind::NetCdf;
    throw FormatNotSupported(path + ": format not recognised (file starts with '" + s.description + "'); " + kSupported);
}

ScalarField readNrrd(const std::string& path, const FieldRequest& req) {
    if (req.hasRegion)
        throw InputError(path + ": a region needs a geographic (NetCDF longitude/latitude) grid, NRRD volumes have none");
    ScalarField f = NrrdReader::read(path, req.memoryBudget);
    if (!req.variable.empty() && req.variable != f.name)
        throw InputError(path + ": no variable '" + req.variable + "' (the NRRD volume holds one field, '" + f.name + "')");
    if (req.verticalScale != 0.0) log::warning(path + ": vertical scale ignored for a NRRD volume");
    return f;
}

}  // namespace

ScalarField readField(const std::string& path, const FieldRequest& req) {
    ScalarField f = kindOf(path) == FileKind::Nrrd ? readNrrd(path, req) : NetcdfReader::read(path, req);
    f.validate();
    return f;
}

std::string describeInput(const std::string& path, std::uint64_t memoryBudget) {
    return kindOf(path) == FileKind::Nrrd ? NrrdReader::describe(path, memoryBudget)
                                          : NetcdfReader::describe(path, memoryBudget);
}

}  // namespace octrace::io

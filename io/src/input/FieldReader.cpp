#include "octrace/io/FieldReader.h"

#include "input/FormatSniffer.h"
#include "input/InputFile.h"
#include "zarr/ZarrStore.h"
#include "octrace/io/DicomReader.h"
#include "octrace/io/NetcdfReader.h"
#include "octrace/io/NrrdReader.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/io/VolumeReader.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <filesystem>
#include <optional>

namespace octrace::io {
namespace {

using detail::FileKind;

const char* kSupported = "supported: NetCDF (.nc, .cdf, .nc4: classic, 64-bit offset, CDF-5, NetCDF-4/HDF5), "
                         "Zarr v2 (a store's folder), "
                         "NRRD (.nrrd, .nhdr), DICOM (a file, a folder or a DICOMDIR), MetaImage (.mhd, .mha), "
                         "NIfTI (.nii, .nii.gz, .hdr), VTK image data (.vti)";

FileKind kindOf(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return detail::sniffFolder(path).kind;  // Zarr store or DICOM folder
    detail::Sniffed s = detail::sniffFormat(path);
    if (s.kind != FileKind::Unknown) return s.kind;
    // No known signature: trust the extension so the format's reader can say what is wrong.
    std::string ext = detail::lower(std::filesystem::path(path).extension().string());
    if (ext == ".nrrd" || ext == ".nhdr") return FileKind::Nrrd;
    if (ext == ".nc" || ext == ".cdf" || ext == ".nc4" || ext == ".netcdf") return FileKind::NetCdf;
    if (ext == ".mhd" || ext == ".mha") return FileKind::MetaImage;
    if (ext == ".nii" || ext == ".hdr" || detail::lower(path).ends_with(".nii.gz")) return FileKind::Nifti;
    if (ext == ".vti") return FileKind::Vti;
    if (ext == ".dcm" || ext == ".dicom" || std::filesystem::path(path).filename() == "DICOMDIR") return FileKind::Dicom;
    const std::string store = zarrStoreOfMetadataFile(path);
    if (!store.empty())
        throw FormatNotSupported(path + ": a metadata file of a Zarr store, which is read by its folder: " + store);
    throw FormatNotSupported(path + ": format not recognised (file starts with '" + s.description + "'); " + kSupported);
}

/// What a volume without geographic axes (NRRD, DICOM) does with a request: one field whose
/// name `--var` must match, no region, no vertical scale.
ScalarField checkVolume(ScalarField f, const std::string& path, const FieldRequest& req, const std::string& format) {
    if (!req.variable.empty() && req.variable != f.name)
        throw InputError(path + ": no variable '" + req.variable + "' (the " + format + " volume holds one field, '" + f.name + "')");
    if (req.verticalScale != 0.0) log::warning(path + ": vertical scale ignored for a " + format + " volume");
    return f;
}

// --region, --depth-range and --time choose among a NetCDF file's axes; other formats have none.
void refuseRegion(const std::string& path, const FieldRequest& req, const std::string& format) {
    if (req.hasRegion)
        throw InputError(path + ": a region needs a geographic (NetCDF longitude/latitude) grid, " + format + " volumes have none");
    if (req.hasDepthRange)
        throw InputError(path + ": a depth range needs a geographic (NetCDF longitude/latitude/depth) grid, " + format +
                         " volumes have none");
    if (!req.time.empty()) throw InputError(path + ": `time` chooses a NetCDF time step, " + format + " volumes have none");
}

void refuseSeries(const std::string& path, const FieldRequest& req) {
    if (!req.series.empty()) throw InputError(path + ": `series` chooses a DICOM series, this input is not DICOM");
}

void refuseVolume(const std::string& path, const FieldRequest& req, const std::string& format) {
    if (req.volume >= 0)
        throw InputError(path + ": `volume` chooses a volume of a DICOM series or a 4-D NIfTI image; " + format + " inputs have none" +
                         (format == "NetCDF" ? " (`time` chooses a time step)" : ""));
}

std::optional<VolumeReader::Format> volumeFormat(FileKind kind) {
    switch (kind) {
        case FileKind::MetaImage: return VolumeReader::Format::MetaImage;
        case FileKind::Nifti: return VolumeReader::Format::Nifti;
        case FileKind::Vti: return VolumeReader::Format::Vti;
        default: return std::nullopt;
    }
}

}  // namespace

std::string zarrStoreOfMetadataFile(const std::string& path) { return detail::storeOfMetadataFile(path); }

InputChoices listInputChoices(const std::string& path, const ReadHooks& hooks) {
    InputChoices c;
    const FileKind kind = kindOf(path);
    if (kind == FileKind::NetCdf || kind == FileKind::Zarr) c.variables = NetcdfReader::volumeVariables(path);
    if (kind == FileKind::Dicom) c.series = DicomReader::listSeries(path, hooks);
    return c;
}

TimeAxis readTimeAxis(const std::string& path, const FieldRequest& req) {
    const FileKind kind = kindOf(path);
    if (kind == FileKind::NetCdf || kind == FileKind::Zarr) return NetcdfReader::timeAxis(path, req);
    TimeAxis axis;
    axis.path = path;
    // A multi-volume DICOM series or a 4-D NIfTI image: its volumes are the steps.
    std::vector<std::string> labels;
    if (kind == FileKind::Dicom) labels = DicomReader::listVolumes(path, req.series);
    else if (kind == FileKind::Nifti) labels = VolumeReader::volumeLabels(path, VolumeReader::Format::Nifti);
    if (labels.size() > 1) {
        axis.name = "volume";
        axis.volumes = true;
        axis.size = labels.size();
        axis.labels = std::move(labels);
        axis.dates.assign(axis.size, "");
    }
    return axis;
}

ScalarField readField(const std::string& path, const FieldRequest& req) {
    ScalarField f;
    const FileKind kind = kindOf(path);
    if (auto format = volumeFormat(kind)) {
        const char* name = VolumeReader::formatName(*format);
        refuseSeries(path, req);
        refuseRegion(path, req, name);
        f = checkVolume(VolumeReader::read(path, *format, req.memoryBudget, req.volume, req.hooks), path, req, name);
        f.validate();
        return f;
    }
    switch (kind) {
        case FileKind::Nrrd:
            refuseSeries(path, req);
            refuseVolume(path, req, "NRRD");
            refuseRegion(path, req, "NRRD");
            f = checkVolume(NrrdReader::read(path, req.memoryBudget), path, req, "NRRD");
            break;
        case FileKind::Dicom:
            refuseRegion(path, req, "DICOM");
            f = checkVolume(DicomReader::read(path, req.series, req.memoryBudget, req.volume, req.acceptPlanar, req.hooks), path, req, "DICOM");
            break;
        default:
            refuseSeries(path, req);
            refuseVolume(path, req, "NetCDF");
            f = NetcdfReader::read(path, req);
    }
    f.validate();
    return f;
}

std::string describeInput(const std::string& path, const FieldRequest& req) {
    const FileKind kind = kindOf(path);
    if (auto format = volumeFormat(kind)) {
        refuseSeries(path, req);
        refuseRegion(path, req, VolumeReader::formatName(*format));
        return VolumeReader::describe(path, *format, req.memoryBudget, req.volume);
    }
    switch (kind) {
        case FileKind::Nrrd:
            refuseSeries(path, req);
            refuseVolume(path, req, "NRRD");
            refuseRegion(path, req, "NRRD");
            return NrrdReader::describe(path, req.memoryBudget);
        case FileKind::Dicom: refuseRegion(path, req, "DICOM"); return DicomReader::describe(path, req.series, req.memoryBudget, req.volume);
        default: refuseSeries(path, req); refuseVolume(path, req, "NetCDF"); return NetcdfReader::describe(path, req);
    }
}

}  // namespace octrace::io

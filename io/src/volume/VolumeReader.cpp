#include "octrace/io/VolumeReader.h"

#include "input/FieldText.h"
#include "input/InputFile.h"
#include "metaimage/MetaImageHeader.h"
#include "volume/VolumeGeometry.h"
#include "volume/VtkSupport.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkXMLImageDataReader.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>

namespace octrace::io {
namespace {

using Format = VolumeReader::Format;

std::string dimsText(ivec3 d) { return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z); }

// Refuses a read whose file-typed samples, their floats and a validity mask exceed the budget.
void checkBudget(const std::string& path, ivec3 dims, std::uint64_t typeSize, std::uint64_t budget) {
    const std::uint64_t n = saturatingMultiply(saturatingMultiply(std::uint64_t(dims.x), std::uint64_t(dims.y)), std::uint64_t(dims.z));
    checkMemoryBudget(path + ": reading " + dimsText(dims) + " samples", saturatingMultiply(n, typeSize + sizeof(float) + 1), budget);
}

// A sample count along one axis, 1..kMaxAxisPoints; `what` names it in the refusal.
int axisSamples(long long n, const std::string& what) {
    if (n < 1 || std::uint64_t(n) > detail::kMaxAxisPoints)
        throw FileError(what + " = " + std::to_string(n) + " samples, must lie in 1.." + std::to_string(detail::kMaxAxisPoints));
    return int(n);
}

// Runs the reader's pipeline; any VTK error becomes a FileError naming the file.
void update(vtkAlgorithm* reader, detail::VtkMessages& messages, const std::string& path, const char* what) {
    reader->Update();
    if (!messages.errors().empty()) throw FileError(path + ": cannot decode the " + what + " data: " + messages.errors());
}

// The samples, NaN/inf marked invalid; then the field is checked.
void finish(ScalarField& f, std::vector<float> values) {
    f.values = std::move(values);
    detail::markNonFinite(f);
    f.validate();
}

ScalarField readMetaImage(const std::string& path, std::uint64_t budget) {
    const detail::MetaImageHeader h = detail::MetaImageHeader::parse(path);
    h.checkData();
    ScalarField f;
    f.source = path;
    f.name = std::filesystem::path(path).stem().string();
    f.dims = h.dims;
    f.origin = h.origin;
    dmat3 axes = h.direction;
    for (int a = 0; a < 3; ++a) axes[a] *= h.spacing[a] / (glm::length(axes[a]) > 0.0 ? glm::length(axes[a]) : 1.0);
    detail::setAxes(axes, f, path + ": MetaImage TransformMatrix");
    f.validateGeometry();
    checkBudget(path, h.dims, h.typeSize, budget);
    finish(f, h.readSamples());
    if (!h.anatomicalOrientation.empty()) f.notes.push_back("MetaImage AnatomicalOrientation: " + h.anatomicalOrientation);
    return f;
}

// NIfTI's world is RAS; octrace's medical volumes are LPS.
const dmat3 kRasToLps(dvec3(-1, 0, 0), dvec3(0, -1, 0), dvec3(0, 0, 1));

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The header of a NIfTI file through `reader` (watched by `messages`), checked.
vtkNIFTIImageHeader* niftiHeader(vtkNIFTIImageReader* reader, detail::VtkMessages& messages, const std::string& path) {
    detail::requireReadableFile(path);
    messages.watch(reader);
    reader->SetFileName(path.c_str());
    reader->UpdateInformation();  // the header only
    if (!messages.errors().empty()) throw FileError(path + ": cannot read the NIfTI header: " + messages.errors());
    vtkNIFTIImageHeader* h = reader->GetNIFTIHeader();
    if (!h) throw FileError(path + ": cannot read the NIfTI header");
    return h;
}

// The volumes of a NIfTI image (dim[4], 1 when 3-D), each labelled by its time when the header
// gives one: toffset + v * pixdim[4] in xyzt_units' time unit ("time 1.5 s"); else "".
std::vector<std::string> niftiVolumeLabels(vtkNIFTIImageHeader* h) {
    const long long volumes = h->GetDim(0) >= 4 ? std::max<long long>(1, h->GetDim(4)) : 1;
    const char* unit = nullptr;
    switch (h->GetXYZTUnits() & 0x38) {  // NIFTI_SEC, NIFTI_MSEC, NIFTI_USEC; Hz, ppm, rad/s are not times
        case 8: unit = "s"; break;
        case 16: unit = "ms"; break;
        case 24: unit = "us"; break;
        default: break;
    }
    const double step = h->GetPixDim(4), offset = h->GetTOffset();
    const bool timed = unit && volumes > 1 && std::isfinite(step) && step > 0.0 && std::isfinite(offset);
    std::vector<std::string> labels(static_cast<std::size_t>(volumes));
    if (timed)
        for (long long v = 0; v < volumes; ++v) labels[std::size_t(v)] = "time " + detail::num(offset + double(v) * step) + " " + unit;
    return labels;
}

// The file that holds a NIfTI image's samples: the file itself (.nii, .nii.gz, .img), else
// the .img (or .img.gz) beside a .hdr, as VTK's reader finds it.
std::string niftiDataFile(const std::string& path) {
    const std::string low = detail::lower(path);
    for (const char* hdr : {".hdr", ".hdr.gz"}) {
        if (!endsWith(low, hdr)) continue;
        const std::string stem = path.substr(0, path.size() - std::strlen(hdr));
        for (const char* img : {".img", ".img.gz", ".IMG", ".IMG.gz"})
            if (std::filesystem::exists(stem + img)) return stem + img;
        throw FileError(path + ": NIfTI/Analyze header without its .img data file");
    }
    return path;
}

// Whether the file's byte order is not the machine's: sizeof_hdr (the header's first 4 bytes,
// 348 for NIfTI-1 and Analyze, 540 for NIfTI-2) reads right only in the file's own order.
bool niftiSwapped(const std::string& path, vtkNIFTIImageReader* reader) {
    std::string header = path;
    const std::string low = detail::lower(path);
    for (const char* img : {".img", ".img.gz"})
        if (endsWith(low, img)) header = path.substr(0, path.size() - std::strlen(img)) + (std::strlen(img) == 4 ? ".hdr" : ".hdr.gz");
    std::uint32_t size = 0;
    if (gzFile g = gzopen(header.c_str(), "rb")) {
        const int got = gzread(g, &size, sizeof size);
        gzclose(g);
        if (got == int(sizeof size)) {
            if (size == 348 || size == 540) return false;
            const std::uint32_t swapped = __builtin_bswap32(size);
            if (swapped == 348 || swapped == 540) return true;
        }
    }
    return reader->GetSwapBytes();
}

// One NIfTI sample type as float: the datatype code's C type, byte-swapped when the file's
// byte order is not the machine's.
template <typename T>
void samplesToFloat(const unsigned char* src, std::size_t n, bool swap, float* dst) {
    for (std::size_t i = 0; i < n; ++i) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, src + i * sizeof(T), sizeof(T));
        if (swap) std::reverse(b, b + sizeof(T));
        T v;
        std::memcpy(&v, b, sizeof(T));
        dst[i] = float(v);
    }
}

// How the samples of one NIfTI datatype become floats.
struct SampleType {
    void (*convert)(const unsigned char*, std::size_t, bool, float*);
    std::size_t bytes;
};

template <typename T>
SampleType sampleType() {
    return {samplesToFloat<T>, sizeof(T)};
}

// The sample type of a NIfTI datatype code with one value per sample, checked against bitpix
// (which sizes the reads); colour, complex and 128-bit types are refused naming the code.
SampleType niftiSampleType(int datatype, int bitpix, const std::string& path) {
    SampleType t{};
    switch (datatype) {
        case 2: t = sampleType<std::uint8_t>(); break;
        case 4: t = sampleType<std::int16_t>(); break;
        case 8: t = sampleType<std::int32_t>(); break;
        case 16: t = sampleType<float>(); break;
        case 64: t = sampleType<double>(); break;
        case 256: t = sampleType<std::int8_t>(); break;
        case 512: t = sampleType<std::uint16_t>(); break;
        case 768: t = sampleType<std::uint32_t>(); break;
        case 1024: t = sampleType<std::int64_t>(); break;
        case 1280: t = sampleType<std::uint64_t>(); break;
        case 128:
        case 2304: throw FileError(path + ": NIfTI datatype " + std::to_string(datatype) + " is colour (RGB/RGBA): a volume needs one value per sample");
        default: throw FileError(path + ": NIfTI datatype " + std::to_string(datatype) + " is not supported (complex or 128-bit samples)");
    }
    if (std::size_t(bitpix) != 8 * t.bytes)
        throw FileError(path + ": NIfTI bitpix " + std::to_string(bitpix) + " does not match datatype " + std::to_string(datatype) + " (" +
                        std::to_string(8 * t.bytes) + " bits)");
    return t;
}

// Closes a gzFile (zlib reads plain files through it too).
struct GzCloser {
    void operator()(gzFile_s* g) const { gzclose(g); }
};

// Reads `bytes` bytes from `g` into `dst`; false when the data end first. A decoding error
// (corrupt compressed data, wrong checksum) is a FileError naming `path`.
bool gzReadAll(gzFile g, unsigned char* dst, std::uint64_t bytes, const std::string& path) {
    while (bytes > 0) {
        const unsigned chunk = unsigned(std::min<std::uint64_t>(bytes, 1u << 30));
        const int got = gzread(g, dst, chunk);
        if (got < 0) {
            int code = Z_OK;
            const char* why = gzerror(g, &code);
            if (code == Z_BUF_ERROR) return false;  // "unexpected end of file": a cut .gz
            throw FileError(path + ": cannot decode the NIfTI data: " + std::string(why && *why ? why : "zlib error"));
        }
        if (got == 0) return false;
        dst += got;
        bytes -= std::uint64_t(got);
    }
    return true;
}

// The samples of volume `chosen` of a NIfTI image, as floats in VTK's slice order (reversed
// when qfac is -1, as the geometry VTK gives is): only that volume is decoded. A plain file is
// read from its offset; a gzipped one is streamed, the volumes before it inflated and skipped
// (gzseek), the ones after it left alone. Progress per slice; cancellation asked before each.
std::vector<float> readNiftiVolume(const std::string& path, vtkNIFTIImageReader* reader, vtkNIFTIImageHeader* h, ivec3 dims,
                                   long long chosen, long long volumes, const ReadHooks& hooks) {
    const SampleType type = niftiSampleType(h->GetDataType(), h->GetBitPix(), path);
    const std::string data = niftiDataFile(path);
    const std::uint64_t typeSize = type.bytes;
    const std::uint64_t plane = std::uint64_t(dims.x) * std::uint64_t(dims.y);
    const std::uint64_t sliceBytes = saturatingMultiply(plane, typeSize), volumeBytes = saturatingMultiply(sliceBytes, std::uint64_t(dims.z));
    // Past 2^62 bytes no file holds the data (and the sums below could wrap): refused as cut.
    constexpr std::uint64_t kNoFileThatLarge = std::uint64_t(1) << 62;
    const std::uint64_t skipped = saturatingMultiply(std::uint64_t(chosen), volumeBytes);
    if (volumeBytes >= kNoFileThatLarge || skipped >= kNoFileThatLarge)
        throw FileError(path + ": NIfTI data truncated: volume " + std::to_string(chosen) + " of " + dimsText(dims) + " x " +
                        std::to_string(h->GetBitPix()) + " bits would end past 2^62 bytes");
    const std::uint64_t start = std::uint64_t(std::max<long long>(0, h->GetVoxOffset())) + skipped;
    const std::string which = volumes > 1 ? "volume " + std::to_string(chosen) + " of " + std::to_string(volumes) + ": " : std::string();
    const std::string need = which + dimsText(dims) + " x " + std::to_string(h->GetBitPix()) + " bits from byte " + std::to_string(start) +
                             " need " + std::to_string(start + volumeBytes) + " bytes";
    const bool gzipped = endsWith(detail::lower(data), ".gz");
    if (!gzipped && detail::fileSize(data) < start + volumeBytes)
        throw FileError(path + ": NIfTI data truncated: " + need + ", the file has " + std::to_string(detail::fileSize(data)));
    std::unique_ptr<gzFile_s, GzCloser> g(gzopen(data.c_str(), "rb"));
    if (!g) throw FileError(data + ": cannot open the NIfTI data");
    gzbuffer(g.get(), 1u << 18);
    const std::string cut = path + ": NIfTI data truncated: " + need + ", the " + (gzipped ? "decompressed data end" : "file ends") + " before";
    if (start > 0 && gzseek64(g.get(), z_off64_t(start), SEEK_SET) != z_off64_t(start)) {
        int code = Z_OK;
        const char* why = gzerror(g.get(), &code);
        if (code != Z_OK && code != Z_BUF_ERROR) throw FileError(path + ": cannot decode the NIfTI data: " + std::string(why ? why : "zlib error"));
        throw FileError(cut);
    }
    const bool swap = niftiSwapped(path, reader);
    const bool reversed = reader->GetQFac() < 0.0;
    // The samples grow slice by slice as they are decoded (a header that claims more than a
    // .gz holds is refused as cut before all of it is allocated), in the file's order; the
    // slices are reversed at the end when qfac is -1.
    std::vector<float> values;
    if (!gzipped) values.reserve(std::size_t(plane) * std::size_t(dims.z));  // the file holds them: checked above
    std::vector<unsigned char> slice(static_cast<std::size_t>(sliceBytes));
    for (int k = 0; k < dims.z; ++k) {
        hooks.checkCancelled(path);
        hooks.report(double(k) / double(dims.z));
        if (!gzReadAll(g.get(), slice.data(), sliceBytes, path)) throw FileError(cut);
        values.resize(std::size_t(plane) * std::size_t(k + 1));
        type.convert(slice.data(), std::size_t(plane), swap, values.data() + std::size_t(plane) * std::size_t(k));
    }
    if (reversed)
        for (int k = 0; k < dims.z / 2; ++k)
            std::swap_ranges(values.begin() + std::ptrdiff_t(plane * std::uint64_t(k)), values.begin() + std::ptrdiff_t(plane * std::uint64_t(k + 1)),
                             values.begin() + std::ptrdiff_t(plane * std::uint64_t(dims.z - 1 - k)));
    // The last volume reaches the end of the compressed stream: reading on checks its CRC.
    unsigned char probe = 0;
    if (gzipped && chosen == volumes - 1) gzReadAll(g.get(), &probe, 1, path);
    hooks.report(1.0);
    return values;
}

ScalarField readNifti(const std::string& path, std::uint64_t budget, int volume, const ReadHooks& hooks) {
    vtkNew<vtkNIFTIImageReader> reader;
    detail::VtkMessages messages;
    vtkNIFTIImageHeader* h = niftiHeader(reader, messages, path);
    const long long rank = h->GetDim(0);
    if (rank < 3 || rank > 7) throw FileError(path + ": NIfTI dim[0] = " + std::to_string(rank) + ": octrace reads 3-D volumes");
    for (int d = 5; d <= rank; ++d)
        if (h->GetDim(d) > 1)
            throw FileError(path + ": NIfTI image has " + std::to_string(h->GetDim(d)) + " values along dimension " + std::to_string(d) +
                            ": octrace reads 3-D volumes and 4-D series of them");
    // A 4-D image is a series of volumes (time points, diffusion directions): `volume` chooses one.
    const long long volumes = rank >= 4 ? std::max<long long>(1, h->GetDim(4)) : 1;
    if (volume >= volumes)
        throw InputError(path + ": no volume " + std::to_string(volume) + ": the NIfTI image holds " +
                         (volumes == 1 ? std::string("one volume (`volume` 0)") : std::to_string(volumes) + " volumes (dim[4]), 0.." + std::to_string(volumes - 1)));
    const long long chosen = std::max(0, volume);
    if (volumes > 1 && volume < 0)
        log::info(path + ": the NIfTI image holds " + std::to_string(volumes) + " volumes (dim[4]); reading volume 0, choose another with `volume`");
    ivec3 dims;
    for (int a = 0; a < 3; ++a) dims[a] = axisSamples(h->GetDim(a + 1), path + ": NIfTI dim[" + std::to_string(a + 1) + "]");
    const int bitpix = h->GetBitPix();
    if (bitpix < 8 || bitpix > 64 || bitpix % 8 != 0)
        throw FileError(path + ": NIfTI bitpix " + std::to_string(bitpix) + " (datatype " + std::to_string(h->GetDataType()) + ") is not supported");
    const std::uint64_t typeSize = std::uint64_t(bitpix / 8);
    ScalarField f;
    f.source = path;
    std::string stem = std::filesystem::path(path).filename().string();
    for (const char* ext : {".nii.gz", ".nii", ".hdr", ".img"})
        if (endsWith(detail::lower(stem), ext)) stem = stem.substr(0, stem.size() - std::strlen(ext));
    f.name = stem;
    f.dims = dims;

    // The matrix from VTK's image coordinates (spacing applied) to RAS; VTK has already
    // reversed the slices when qfac is -1 and adjusted both matrices to match.
    vtkMatrix4x4* m = nullptr;
    std::string which;
    if (h->GetSFormCode() > 0 && reader->GetSFormMatrix()) {
        m = reader->GetSFormMatrix();
        which = "sform (code " + std::to_string(h->GetSFormCode()) + ")";
    } else if (h->GetQFormCode() > 0 && reader->GetQFormMatrix()) {
        m = reader->GetQFormMatrix();
        which = "qform (code " + std::to_string(h->GetQFormCode()) + ")";
    }
    const double* spacing = reader->GetDataSpacing();
    const double* origin = reader->GetDataOrigin();
    dmat3 axes(1.0);
    dvec3 start(0.0);
    for (int a = 0; a < 3; ++a) {
        if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
            throw FileError(path + ": NIfTI pixdim[" + std::to_string(a + 1) + "] = " + detail::num(spacing[a]) + " must be positive");
        dvec3 column(0.0);
        column[a] = 1.0;
        if (m) column = dvec3(m->GetElement(0, a), m->GetElement(1, a), m->GetElement(2, a));
        axes[a] = column * spacing[a];
        start += column * origin[a];
    }
    if (m) {
        start += dvec3(m->GetElement(0, 3), m->GetElement(1, 3), m->GetElement(2, 3));
        axes = kRasToLps * axes;
        start = kRasToLps * start;
        f.notes.push_back("NIfTI " + which + ", RAS turned into LPS (x and y negated)");
        f.patientLps = true;
    } else {
        f.notes.push_back("NIfTI without qform or sform: grid axes scaled by pixdim");
    }
    f.origin = start;
    detail::setAxes(axes, f, path + ": NIfTI " + (which.empty() ? std::string("pixdim") : which));
    f.validateGeometry();
    // Only the volume asked for is decoded (readNiftiVolume), so only it counts.
    checkBudget(path, dims, typeSize, budget);
    if (volumes > 1) {
        const std::string label = niftiVolumeLabels(h)[std::size_t(chosen)];
        f.notes.push_back("volume " + std::to_string(chosen) + " of " + std::to_string(volumes) + " (NIfTI dim[4])" +
                          (label.empty() ? std::string() : ": " + label));
    }
    std::vector<float> values = readNiftiVolume(path, reader, h, dims, chosen, volumes, hooks);
    const double slope = h->GetSclSlope(), inter = h->GetSclInter();
    if (slope != 0.0 && std::isfinite(slope) && std::isfinite(inter) && (slope != 1.0 || inter != 0.0)) {
        for (float& v : values) v = float(double(v) * slope + inter);
        f.notes.push_back("NIfTI scl_slope " + detail::num(slope) + ", scl_inter " + detail::num(inter) + " applied");
    }
    finish(f, std::move(values));
    return f;
}

ScalarField readVti(const std::string& path, std::uint64_t budget) {
    detail::requireReadableFile(path);
    vtkNew<vtkXMLImageDataReader> reader;
    detail::VtkMessages messages;
    messages.watch(reader);
    reader->SetFileName(path.c_str());
    reader->UpdateInformation();
    if (!messages.errors().empty()) throw FileError(path + ": cannot read the VTK image data file: " + messages.errors());
    int extent[6] = {0, -1, 0, -1, 0, -1};
    vtkInformation* info = reader->GetOutputInformation(0);
    if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
        throw FileError(path + ": VTK XML file without an ImageData extent");
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
    ivec3 dims;
    for (int a = 0; a < 3; ++a)
        dims[a] = axisSamples((long long)extent[2 * a + 1] - extent[2 * a] + 1,
                              path + ": ImageData extent " + std::to_string(extent[2 * a]) + ".." + std::to_string(extent[2 * a + 1]) +
                                  " along axis " + std::to_string(a) + ",");
    ScalarField f;
    f.source = path;
    f.dims = dims;
    // The sample type is not known before the data are read: budget for doubles.
    checkBudget(path, dims, sizeof(double), budget);
    update(reader, messages, path, "VTK image data");
    vtkImageData* image = reader->GetOutput();
    vtkPointData* pd = image ? image->GetPointData() : nullptr;
    if (!pd || pd->GetNumberOfArrays() == 0) throw FileError(path + ": no point data array in the ImageData");
    if (!pd->GetScalars()) pd->SetScalars(pd->GetArray(0));
    if (pd->GetNumberOfArrays() > 1) f.notes.push_back("VTI: " + std::to_string(pd->GetNumberOfArrays()) + " point arrays, the active scalars read");
    const char* name = pd->GetScalars() ? pd->GetScalars()->GetName() : nullptr;
    f.name = name && *name ? name : std::filesystem::path(path).stem().string();

    const double* spacing = image->GetSpacing();
    const double* origin = image->GetOrigin();
    const double* d = image->GetDirectionMatrix()->GetData();  // row-major
    dmat3 axes;
    for (int a = 0; a < 3; ++a) axes[a] = dvec3(d[a], d[3 + a], d[6 + a]) * spacing[a];
    detail::setAxes(axes, f, path + ": ImageData Direction");
    f.origin = dvec3(origin[0], origin[1], origin[2]);
    for (int a = 0; a < 3; ++a) f.origin += axes[a] * double(extent[2 * a]);
    f.validateGeometry();
    finish(f, detail::scalarsAsFloat(image, f.sampleCount(), path));
    return f;
}

}  // namespace

const char* VolumeReader::formatName(Format format) {
    switch (format) {
        case Format::MetaImage: return "MetaImage";
        case Format::Nifti: return "NIfTI";
        default: return "VTK image data";
    }
}

ScalarField VolumeReader::read(const std::string& path, Format format, std::uint64_t memoryBudget, int volume, const ReadHooks& hooks) {
    if (volume >= 0 && format != Format::Nifti)
        throw InputError(path + ": `volume` chooses a volume of a DICOM series or a 4-D NIfTI image; a " +
                         std::string(formatName(format)) + " file holds one");
    switch (format) {
        case Format::MetaImage: return readMetaImage(path, memoryBudget);
        case Format::Nifti: return readNifti(path, memoryBudget, volume, hooks);
        default: return readVti(path, memoryBudget);
    }
}

std::vector<std::string> VolumeReader::volumeLabels(const std::string& path, Format format) {
    if (format != Format::Nifti) return {""};
    vtkNew<vtkNIFTIImageReader> reader;
    detail::VtkMessages messages;
    return niftiVolumeLabels(niftiHeader(reader, messages, path));
}

std::string VolumeReader::describe(const std::string& path, Format format, std::uint64_t memoryBudget, int volume) {
    const ScalarField f = read(path, format, memoryBudget, volume);
    std::ostringstream s;
    s << path << "\nformat: " << formatName(format) << "\n";
    const std::vector<std::string> labels = volumeLabels(path, format);
    if (labels.size() > 1)
        s << detail::describeVolumeList(labels, std::size_t(f.dims.z)) << "chosen: volume " << (volume < 0 ? 0 : volume) << "\n";
    s << detail::describeVolume(f);
    return s.str();
}

}  // namespace octrace::io

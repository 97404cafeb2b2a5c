#include "octrace/io/VolumeWriter.h"

#include "input/InputFile.h"
#include "volume/VolumeGeometry.h"
#include "volume/VtkSupport.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataWriter.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <span>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace octrace::io {
namespace {

std::string triple(const dvec3& v) {
    return detail::exactNumber(v.x) + " " + detail::exactNumber(v.y) + " " + detail::exactNumber(v.z);
}

void writeMetaImage(const ScalarField& f, const std::string& path, bool local) {
    dvec3 origin, spacing;
    detail::uniformGrid(f, path, "MetaImage", origin, spacing);
    const std::string rawName = fs::path(path).stem().string() + ".raw";
    std::ostringstream h;
    h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\nCompressedData = False\n";
    h << "TransformMatrix = " << triple(f.direction[0]) << " " << triple(f.direction[1]) << " " << triple(f.direction[2]) << "\n";
    h << "Offset = " << triple(origin) << "\nElementSpacing = " << triple(spacing) << "\n";
    h << "DimSize = " << f.dims.x << " " << f.dims.y << " " << f.dims.z << "\nElementNumberOfChannels = 1\n";
    h << "ElementType = MET_FLOAT\nElementDataFile = " << (local ? std::string("LOCAL") : rawName) << "\n";
    const std::string text = h.str();
    std::vector<std::uint8_t> bytes;
    if (local) bytes.assign(text.begin(), text.end());
    detail::appendFloatsLE(f, bytes);
    if (local) {
        writeFileAtomically(path, std::span<const std::uint8_t>(bytes));
    } else {
        // The data first: a header is never left naming missing or partial data.
        writeFileAtomically((fs::path(path).parent_path() / rawName).string(), std::span<const std::uint8_t>(bytes));
        writeFileAtomically(path, text);
    }
}

// The field as VTK image data at origin 0 with the field's spacing (and, for VTI, its
// origin and direction), float samples, invalid ones NaN.
vtkNew<vtkImageData> toImage(const ScalarField& f, const dvec3& spacing) {
    vtkNew<vtkImageData> image;
    image->SetDimensions(f.dims.x, f.dims.y, f.dims.z);
    image->SetSpacing(spacing.x, spacing.y, spacing.z);
    vtkNew<vtkFloatArray> values;
    values->SetName(f.name.empty() ? "values" : f.name.c_str());
    values->SetNumberOfValues(vtkIdType(f.values.size()));
    for (std::size_t i = 0; i < f.values.size(); ++i) values->SetValue(vtkIdType(i), f.isValid(i) ? f.values[i] : std::nanf(""));
    image->GetPointData()->SetScalars(values);
    return image;
}

void writeVti(const ScalarField& f, const std::string& path) {
    dvec3 origin, spacing;
    detail::uniformGrid(f, path, "VTK image data", origin, spacing);
    vtkNew<vtkImageData> image = toImage(f, spacing);
    image->SetOrigin(origin.x, origin.y, origin.z);
    image->SetDirectionMatrix(f.direction[0].x, f.direction[1].x, f.direction[2].x, f.direction[0].y, f.direction[1].y,
                              f.direction[2].y, f.direction[0].z, f.direction[1].z, f.direction[2].z);
    vtkNew<vtkXMLImageDataWriter> writer;
    detail::VtkMessages messages;
    messages.watch(writer);
    writer->SetInputData(image);
    writer->WriteToOutputStringOn();
    writer->SetDataModeToBinary();
    if (!writer->Write() || !messages.errors().empty())
        throw OutputError(path + ": VTK cannot write the image data: " + messages.errors());
    writeFileAtomically(path, writer->GetOutputString());
}

void writeNifti(const ScalarField& f, const std::string& path, const VolumeWriteOptions& options) {
    dvec3 origin, spacing;
    detail::uniformGrid(f, path, "NIfTI", origin, spacing);
    vtkNew<vtkImageData> image = toImage(f, spacing);
    // LPS -> RAS: x and y negated; the matrix maps VTK's (spacing-scaled) coordinates to RAS.
    vtkNew<vtkMatrix4x4> m;
    for (int r = 0; r < 3; ++r) {
        const double flip = r < 2 ? -1.0 : 1.0;
        for (int c = 0; c < 3; ++c) m->SetElement(r, c, flip * f.direction[c][r]);
        m->SetElement(r, 3, flip * origin[r]);
    }
    vtkNew<vtkNIFTIImageWriter> writer;
    detail::VtkMessages messages;
    messages.watch(writer);
    writer->SetInputData(image);
    if (options.niftiSform) writer->SetSFormMatrix(m);
    if (options.niftiQform && m->Determinant() > 0.0) writer->SetQFormMatrix(m);
    writer->SetDescription(f.name.substr(0, 79).c_str());

    // VTK writes to a name; that name is a temporary beside the target (same extension, which
    // chooses gzip), renamed over the target once VTK is done.
    static std::atomic<unsigned> counter{0};
    const fs::path target(path);
    const std::string ext = detail::lower(path).ends_with(".nii.gz") ? ".nii.gz" : ".nii";
    const fs::path temp = target.parent_path() / (std::string(".") + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                                                  std::to_string(counter++) + ext);
    writer->SetFileName(temp.string().c_str());
    writer->Write();
    std::error_code ec;
    if (!messages.errors().empty() || !fs::is_regular_file(temp, ec)) {
        fs::remove(temp, ec);
        throw OutputError(path + ": VTK cannot write the NIfTI file" + (messages.errors().empty() ? std::string() : ": " + messages.errors()));
    }
    fs::rename(temp, target, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw OutputError(path + ": cannot rename the written NIfTI file into place: " + ec.message());
    }
}

}  // namespace

void VolumeWriter::write(const ScalarField& field, const std::string& path, const VolumeWriteOptions& options) {
    const std::string p = detail::lower(path);
    if (p.ends_with(".mhd")) return writeMetaImage(field, path, false);
    if (p.ends_with(".mha")) return writeMetaImage(field, path, true);
    if (p.ends_with(".nii") || p.ends_with(".nii.gz")) return writeNifti(field, path, options);
    if (p.ends_with(".vti")) return writeVti(field, path);
    throw OutputError(path + ": unknown volume format (write .mhd, .mha, .nii, .nii.gz or .vti)");
}

}  // namespace octrace::io

#include "octrace/io/NrrdReader.h"

#include "input/FieldText.h"
#include "input/InputFile.h"
#include "nrrd/NrrdHeader.h"
#include "volume/VolumeGeometry.h"
#include "volume/VtkSupport.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <vtkCharArray.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNrrdReader.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace octrace::io {
namespace {

// vtkNrrdReader reads rows bottom-up for left-handed spaces ("3D-left-handed", LAS); octrace
// keeps the file's sample order so that NRRD's space directions apply unchanged. Created with
// `new`, never through the object factory (which may hand out the MPI vtkPNrrdReader).
//
// It also ends the header text with a newline: vtkNrrdReader's header loop stops at an empty
// line, and when the last line of a detached header has no newline, std::getline fails at
// the end without clearing the line, so VTK handled that last line again forever (found by
// fuzz_nrrd; NrrdHeader refuses NUL bytes, so the text is the whole buffer).
class FileOrderNrrdReader : public vtkNrrdReader {
public:
    static FileOrderNrrdReader* New();
    vtkTypeMacro(FileOrderNrrdReader, vtkNrrdReader)

protected:
    FileOrderNrrdReader() = default;
    int ReadHeader(vtkCharArray* headerBuffer) override {
        const vtkIdType n = headerBuffer->GetNumberOfTuples();  // the text and its terminating NUL
        if (n >= 2 && headerBuffer->GetValue(n - 2) != '\n') {
            headerBuffer->SetValue(n - 1, '\n');
            headerBuffer->InsertNextValue('\0');
        }
        int ok = vtkNrrdReader::ReadHeader(headerBuffer);
        this->FileLowerLeft = 1;
        return ok;
    }
};
vtkStandardNewMacro(FileOrderNrrdReader)

// vtkNrrdReader reports a short gzip stream as "Couldn't read gzip data from nrrd file: F N/M, ...".
bool gzipShortfall(const std::string& errors, std::size_t& need, std::size_t& got) {
    if (errors.find("Couldn't read gzip data") == std::string::npos) return false;
    auto end = errors.find(", GetHeaderSize()");
    if (end == std::string::npos) return false;
    auto start = errors.rfind(' ', end);
    if (start == std::string::npos) return false;
    long long n = -1, m = -1;
    if (std::sscanf(errors.substr(start + 1, end - start - 1).c_str(), "%lld/%lld", &n, &m) != 2 || n < 0) return false;
    need = std::size_t(n);
    got = std::size_t(std::max(0LL, m));
    return true;
}

std::vector<float> decodeSamples(const detail::NrrdHeader& h) {
    vtkNew<FileOrderNrrdReader> reader;
    detail::VtkMessages messages;
    messages.watch(reader);
    reader->SetFileName(h.path.c_str());
    reader->Update();

    vtkImageData* image = reader->GetOutput();
    vtkDataArray* array = image && image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
    std::size_t need = 0, got = 0;
    if (gzipShortfall(messages.errors(), need, got))
        throw FileError(h.path + ": gzip data truncated: header says " + std::to_string(h.sizes.x) + "x" +
                        std::to_string(h.sizes.y) + "x" + std::to_string(h.sizes.z) + " " + h.type + " = " +
                        std::to_string(need) + " bytes, the stream inflates to " + std::to_string(got));
    if (!messages.errors().empty() || !array)
        throw FileError(h.path + ": cannot decode the " + h.encoding + " data" +
                        (messages.errors().empty() ? std::string() : ": " + messages.errors()));
    // The header says 3-D scalar; VTK may see a short first axis as components.
    return detail::scalarsAsFloat(image, h.sampleCount(), h.path, false);
}

// NRRD allows any basis, octrace needs an orthogonal one (a sheared grid is not a ScalarField).
void setGeometry(const detail::NrrdHeader& h, ScalarField& f) {
    f.origin = h.origin;
    if (!h.hasDirections) {
        f.spacing = h.spacings;
        f.direction = dmat3(1.0);
        return;
    }
    detail::setAxes(h.directions, f, h.path + ": space directions");
}

}  // namespace

ScalarField NrrdReader::read(const std::string& path, std::uint64_t memoryBudget) {
    detail::requireReadableFile(path);
    auto header = detail::NrrdHeader::parse(path);
    header.checkData();

    ScalarField f;
    f.source = path;
    f.name = header.content.empty() ? std::filesystem::path(path).stem().string() : header.content;
    if (auto it = header.keyValues.find("units"); it != header.keyValues.end()) f.units = it->second;
    f.dims = header.sizes;
    setGeometry(header, f);
    f.validateGeometry();
    // VTK's array of the file's type, our floats, and a validity mask when samples can be NaN.
    const std::uint64_t bytesPerSample = header.typeSize + sizeof(float) + (header.type == "float" || header.type == "double");
    checkMemoryBudget(path + ": reading " + std::to_string(header.sizes.x) + "x" + std::to_string(header.sizes.y) + "x" +
                          std::to_string(header.sizes.z) + " " + header.type + " samples",
                      saturatingMultiply(header.sampleCount(), bytesPerSample), memoryBudget);
    f.values = decodeSamples(header);
    detail::markNonFinite(f);
    if (!header.space.empty()) f.notes.push_back("NRRD space: " + header.space);
    f.patientLps = header.space == "left-posterior-superior" || header.space == "LPS";
    f.validate();
    return f;
}

std::string NrrdReader::describe(const std::string& path, std::uint64_t memoryBudget) {
    ScalarField f = read(path, memoryBudget);
    auto h = detail::NrrdHeader::parse(path);
    std::ostringstream s;
    s << path << "\n";
    s << "format: NRRD (" << h.magic << "), " << h.type << ", " << h.encoding << " encoding, "
      << (h.dataFiles.empty() ? std::string("attached data")
                              : std::to_string(h.dataFiles.size()) + " detached data file(s)") << "\n";
    s << detail::describeVolume(f);
    return s.str();
}

}  // namespace octrace::io

#include "octrace/io/NrrdReader.h"

#include "FieldText.h"
#include "InputFile.h"
#include "NrrdHeader.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <vtkCallbackCommand.h>
#include <vtkCharArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkNrrdReader.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
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

// VTK's text without its "ERROR: In file, line N" line and "Class (0x...): " prefix, on one line.
std::string cleanVtkText(const std::string& raw) {
    std::istringstream in(raw);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        line = detail::trim(line);
        if (line.empty() || line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0) continue;
        auto p = line.find("(0x");
        auto q = line.find("): ");
        if (p != std::string::npos && q != std::string::npos && p < q) line = line.substr(q + 3);
        out += (out.empty() ? "" : " ") + line;
    }
    return out;
}

// Collects VTK error and warning text instead of letting VTK print it.
struct VtkMessages {
    std::string errors;
    static void onEvent(vtkObject*, unsigned long event, void* clientData, void* callData) {
        auto* self = static_cast<VtkMessages*>(clientData);
        std::string text = callData ? cleanVtkText(static_cast<const char*>(callData)) : std::string();
        if (event == vtkCommand::ErrorEvent) {
            if (!self->errors.empty()) self->errors += "; ";
            self->errors += text;
        } else {
            log::debug("VTK: " + text);
        }
    }
};

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

template <typename T>
void toFloat(const T* in, std::size_t n, std::vector<float>& out) {
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(in[i]);
}

std::vector<float> decodeSamples(const detail::NrrdHeader& h) {
    vtkNew<FileOrderNrrdReader> reader;
    VtkMessages messages;
    vtkNew<vtkCallbackCommand> callback;
    callback->SetCallback(&VtkMessages::onEvent);
    callback->SetClientData(&messages);
    reader->AddObserver(vtkCommand::ErrorEvent, callback);
    reader->AddObserver(vtkCommand::WarningEvent, callback);
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback);
    reader->GetExecutive()->AddObserver(vtkCommand::WarningEvent, callback);
    reader->SetFileName(h.path.c_str());
    reader->Update();

    vtkImageData* image = reader->GetOutput();
    vtkDataArray* array = image && image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
    std::size_t need = 0, got = 0;
    if (gzipShortfall(messages.errors, need, got))
        throw FileError(h.path + ": gzip data truncated: header says " + std::to_string(h.sizes.x) + "x" +
                        std::to_string(h.sizes.y) + "x" + std::to_string(h.sizes.z) + " " + h.type + " = " +
                        std::to_string(need) + " bytes, the stream inflates to " + std::to_string(got));
    if (!messages.errors.empty() || !array)
        throw FileError(h.path + ": cannot decode the " + h.encoding + " data" +
                        (messages.errors.empty() ? std::string() : ": " + messages.errors));
    std::size_t n = std::size_t(array->GetNumberOfValues());
    if (n != h.sampleCount())
        throw FileError(h.path + ": decoded " + std::to_string(n) + " samples, header says " +
                        std::to_string(h.sampleCount()));

    std::vector<float> values;
    switch (array->GetDataType()) {
        vtkTemplateMacro(toFloat(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), n, values));
        default:
            throw FileError(h.path + ": VTK decoded an unexpected sample type " + std::string(array->GetDataTypeAsString()));
    }
    return values;
}

// Splits `space directions` into unit columns and lengths; NRRD allows any basis, octrace
// needs an orthogonal one (a sheared grid is not a ScalarField).
void setGeometry(const detail::NrrdHeader& h, ScalarField& f) {
    f.origin = h.origin;
    if (!h.hasDirections) {
        f.spacing = h.spacings;
        f.direction = dmat3(1.0);
        return;
    }
    for (int a = 0; a < 3; ++a) {
        double len = glm::length(h.directions[a]);
        f.spacing[a] = len;
        f.direction[a] = h.directions[a] / len;
    }
    for (int a = 0; a < 3; ++a) {
        int b = (a + 1) % 3;
        double c = glm::dot(f.direction[a], f.direction[b]);
        if (std::abs(c) > 1e-4) {
            double deg = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
            throw FileError(h.path + ": space directions of axes " + std::to_string(std::min(a, b)) + " and " +
                            std::to_string(std::max(a, b)) + " are not perpendicular (" + detail::num(deg) +
                            " degrees): sheared grids are not supported");
        }
    }
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

    std::size_t bad = 0;
    for (float v : f.values) bad += std::isfinite(v) ? 0 : 1;
    if (bad > 0) {
        f.valid.resize(f.values.size());
        for (std::size_t i = 0; i < f.values.size(); ++i) f.valid[i] = std::isfinite(f.values[i]) ? 1 : 0;
        f.notes.push_back(std::to_string(bad) + " NaN/inf samples marked invalid");
    }
    if (!header.space.empty()) f.notes.push_back("NRRD space: " + header.space);
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

#include "volume/VtkSupport.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>

#include <algorithm>
#include <sstream>

namespace octrace::io::detail {
namespace {

template <typename T>
void toFloat(const T* in, std::size_t n, std::vector<float>& out) {
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<float>(in[i]);
}

// VTK objects that nobody observes (e.g. the XML parser inside vtkXMLImageDataReader) print
// through the output window; their text goes to log::debug instead of stderr. The reader that
// owns them reports the failure itself as an error event.
class LogOutputWindow : public vtkOutputWindow {
public:
    static LogOutputWindow* New();
    vtkTypeMacro(LogOutputWindow, vtkOutputWindow)
    void DisplayText(const char* text) override { log::debug("VTK: " + cleanVtkText(text ? text : "")); }

protected:
    LogOutputWindow() = default;
};
vtkStandardNewMacro(LogOutputWindow)

void routeVtkOutputToLog() {
    static const bool once = [] {
        vtkNew<LogOutputWindow> window;
        vtkOutputWindow::SetInstance(window);
        // VTK 9 also sends error text through its logger (loguru) straight to stderr.
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
        return true;
    }();
    (void)once;
}

}  // namespace

std::string cleanVtkText(const std::string& raw) {
    std::istringstream in(raw);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        line = trim(line);
        if (line.empty() || line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0) continue;
        auto p = line.find("(0x");
        auto q = line.find("): ");
        if (p != std::string::npos && q != std::string::npos && p < q) line = line.substr(q + 3);
        out += (out.empty() ? "" : " ") + line;
    }
    return out;
}

void VtkMessages::onEvent(vtkObject*, unsigned long event, void* clientData, void* callData) {
    auto* self = static_cast<VtkMessages*>(clientData);
    std::string text = callData ? cleanVtkText(static_cast<const char*>(callData)) : std::string();
    // The pipeline's "Algorithm vtkX(0x...) returned failure for request: vtkInformation (0x...)
    // Debug: Off Modified Time: ..." follows the reader's own error and only dumps the request:
    // dropped after one, cut to its first words when it is the only one.
    if (const auto at = text.find(" returned failure for request"); event == vtkCommand::ErrorEvent && at != std::string::npos) {
        if (!self->errors_.empty()) {
            log::debug("VTK: " + text);
            return;
        }
        const auto address = text.find("(0x");
        text = text.substr(0, std::min(at, address)) + " failed";
    }
    if (event == vtkCommand::ErrorEvent) {
        if (!self->errors_.empty()) self->errors_ += "; ";
        self->errors_ += text;
    } else {
        log::debug("VTK: " + text);
    }
}

void VtkMessages::watch(vtkAlgorithm* algorithm) {
    routeVtkOutputToLog();
    vtkNew<vtkCallbackCommand> callback;
    callback->SetCallback(&VtkMessages::onEvent);
    callback->SetClientData(this);
    for (vtkObject* o : {static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive())}) {
        o->AddObserver(vtkCommand::ErrorEvent, callback);
        o->AddObserver(vtkCommand::WarningEvent, callback);
    }
}

std::vector<float> scalarsAsFloat(vtkImageData* image, std::size_t expected, const std::string& path, bool oneComponent) {
    vtkDataArray* array = image && image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
    if (!array) throw FileError(path + ": no samples decoded");
    if (oneComponent && array->GetNumberOfComponents() != 1)
        throw FileError(path + ": " + std::to_string(array->GetNumberOfComponents()) +
                        " components per sample (colour or vector data): a volume needs one value per sample");
    const std::size_t n = std::size_t(array->GetNumberOfValues());
    if (n != expected)
        throw FileError(path + ": decoded " + std::to_string(n) + " samples, the header says " + std::to_string(expected));
    std::vector<float> values;
    switch (array->GetDataType()) {
        vtkTemplateMacro(toFloat(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), n, values));
        default:
            throw FileError(path + ": VTK decoded an unexpected sample type " + std::string(array->GetDataTypeAsString()));
    }
    return values;
}

}  // namespace octrace::io::detail

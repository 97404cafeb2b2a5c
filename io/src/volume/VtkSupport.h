#pragma once
// What the readers built on VTK share (internal to octrace_io): VTK's error text collected
// instead of printed, and a decoded image's scalars as floats.
#include <cstddef>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkObject;
class vtkImageData;

namespace octrace::io::detail {

/// VTK's text without its "ERROR: In file, line N" line and "Class (0x...): " prefix, on one line.
std::string cleanVtkText(const std::string& raw);

/// Collects the error events of an algorithm (and its executive) instead of letting VTK print
/// them; warnings go to log::debug. Watch before Update().
class VtkMessages {
public:
    void watch(vtkAlgorithm* algorithm);
    const std::string& errors() const { return errors_; }

private:
    static void onEvent(vtkObject*, unsigned long event, void* clientData, void* callData);
    std::string errors_;
};

/// The scalars of `image` as floats, `expected` values in all. With `oneComponent`, several
/// components per sample (colour, vectors) are refused first.
/// @throws FileError "PATH: ..." when there are none, several components, or another count.
std::vector<float> scalarsAsFloat(vtkImageData* image, std::size_t expected, const std::string& path, bool oneComponent = true);

}  // namespace octrace::io::detail

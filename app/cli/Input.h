#pragma once
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <string>

namespace octrace::cli {
/// Reads INPUT: a file through io::readField, or "analytic:NAME[:SAMPLES]" (default 65 samples).
ScalarField loadField(const std::string& input, const io::FieldRequest& req);
/// Text for `octrace info` (`req.series` chooses a DICOM series).
std::string describe(const std::string& input, const io::FieldRequest& req = {});
}  // namespace octrace::cli

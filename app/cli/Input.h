#pragma once
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstdint>
#include <string>

namespace octrace::cli {
/// Reads INPUT: a file through io::readField, or "analytic:NAME[:SAMPLES]" (default 65 samples).
/// Both refuse (LimitError) samples that would need more than req.memoryBudget.
ScalarField loadField(const std::string& input, const io::FieldRequest& req);
/// Text for `octrace info` (`req.series` chooses a DICOM series; reads that would need more
/// than `req.memoryBudget` bytes, 0 = no limit, are left out or refused: io::describeInput).
std::string describe(const std::string& input, const io::FieldRequest& req = {});
}  // namespace octrace::cli

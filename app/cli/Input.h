#pragma once
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstdint>
#include <string>

namespace octrace::cli {
/// Reads INPUT: a file through io::readField, or "analytic:NAME[:SAMPLES]" (default 65 samples).
/// Both refuse (LimitError) samples that would need more than req.memoryBudget.
ScalarField loadField(const std::string& input, const io::FieldRequest& req);
/// Text for `octrace info`; reads that would need more than `memoryBudget` bytes (0 = no
/// limit) are left out or refused (see io::describeInput).
std::string describe(const std::string& input, std::uint64_t memoryBudget);
}  // namespace octrace::cli

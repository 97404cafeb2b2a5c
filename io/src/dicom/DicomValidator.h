#pragma once
// Our own strict walk over a DICOM file's structure, made before GDCM reads the file
// (internal to octrace_io; no GDCM here). Debian builds GDCM with assertions on, and GDCM's
// fallback paths on a corrupt file (an element longer than the file, for one) abort the
// process; a file that passes this walk has every declared length inside its container, so
// GDCM never meets one of those. See docs/dev/fuzzing.md ("The DICOM pre-validator").
#include <cstddef>
#include <cstdint>
#include <string>

namespace octrace::io::detail {

/// Nested sequences deeper than this are refused (enhanced multi-frame images use 3 or 4).
constexpr int kMaxDicomSequenceDepth = 32;

/// Validates `size` bytes of a DICOM file (`name` is only used in messages). Accepted layouts:
/// the 128-byte preamble and "DICM", or no preamble with the file starting with the file
/// meta group or (a legacy ACR-NEMA style data set, little endian) with an element of group
/// 0008. The meta group is explicit VR little endian, opens with its group length and
/// declares a transfer syntax GDCM knows; the data set (at least one element) is walked in
/// it (implicit VR LE, explicit VR LE including every encapsulated one, explicit VR BE;
/// deflated and private ones are refused). Every element, item and fragment must fit in its
/// container (item, sequence, file), lengths must be even, items and delimiters where they
/// belong, and the data set must end exactly at the end of the file. Linear in the number of elements;
/// recursion bounded by kMaxDicomSequenceDepth.
/// @return false when the bytes do not look like DICOM at all (reason in `whyNot`, starting
///         with "not a DICOM file").
/// @throws FileError "NAME: DICOM structure broken at byte N: WHAT" (one line) for a file
///         that looks like DICOM but whose structure is broken or unsupported.
bool validateDicomBytes(const std::uint8_t* data, std::size_t size, const std::string& name, std::string& whyNot);

/// validateDicomBytes() over the file, memory-mapped (read once, never copied).
/// @throws InputError when the file cannot be opened or mapped; FileError as above.
bool validateDicomFile(const std::string& file, std::string& whyNot);

}  // namespace octrace::io::detail

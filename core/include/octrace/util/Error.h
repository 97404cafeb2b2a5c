#pragma once
/// @file Error.h
/// The exceptions of octrace. Library code throws these and never exits; the CLI maps
/// them to exit codes (UsageError -> 2, everything else -> 1).
#include <stdexcept>
#include <string>

namespace octrace {

/// Root of every exception octrace throws on purpose.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Something wrong with how the program was asked to work (bad option value, bad parameter).
class UsageError : public Error {
public:
    using Error::Error;
};

/// Something found by reading an input: missing, unreadable, broken, or not what was asked.
class InputError : public Error {
public:
    using Error::Error;
};

/// The file is not of a format this reader handles (tell apart from a broken file).
class FormatNotSupported : public InputError {
public:
    using InputError::InputError;
};

/// The file is of the right format but broken or inconsistent.
class FileError : public InputError {
public:
    using InputError::InputError;
};

/// The input is fine but the requested result is empty (no boundary voxel, all masked, ...).
class EmptyResultError : public InputError {
public:
    using InputError::InputError;
};

/// The job would need more than a limit it was given allows (the memory budget, see
/// util/Memory.h): refused before the work, or stopped cleanly while the limit is crossed.
class LimitError : public Error {
public:
    using Error::Error;
};

/// The caller asked the work to stop (e.g. BuildOptions::cancelled, a Cancel button): not a
/// failure of the input or of the program.
class CancelledError : public Error {
public:
    using Error::Error;
};

/// Writing an output failed.
class OutputError : public Error {
public:
    using Error::Error;
};

}  // namespace octrace

#pragma once
// What the files of the Python module share (internal to app/python/src): the settings as the
// Python layer hands them over, running work off the calling thread, and the field object.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/model/Settings.h"

#include <nanobind/nanobind.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace nb = nanobind;
using namespace nb::literals;

namespace octrace::python {

/// (key, the value as text) in the order given; a repeatable setting (`cut`) comes once per value.
using Settings = std::vector<std::pair<std::string, std::string>>;

/// Runs `work` on a worker thread with the GIL released. Every 20 ms (or as soon as the work
/// ends) the calling thread takes the GIL back to check for signals (Ctrl-C sets `cancel`, the
/// work's BuildHooks see it and stop with CancelledError; the call raises KeyboardInterrupt)
/// and to call `progress` with the latest `fraction`. Exceptions of the work are rethrown on
/// the calling thread.
void interruptible(const std::function<void()>& work, std::atomic<bool>& cancel, const std::atomic<double>* fraction = nullptr,
                   const nb::object& progress = nb::none());

/// interruptible() for work that returns a value.
template <class F>
auto runInterruptible(F&& work) {
    std::optional<decltype(work())> out;
    std::atomic<bool> cancel{false};
    interruptible([&] { out.emplace(work()); }, cancel);
    return std::move(*out);
}

/// Applies `settings` to `targets` in the order given (model::applySetting); a key with no
/// place there is refused (the Python layer checks keywords first).
void applySettings(const Settings& settings, const model::SettingTargets& targets);

/// The request the reader settings make (var, region, time, ...), with the memory budget.
io::FieldRequest readerRequest(const Settings& settings);

/// A field read once (a file's variable, xarray's arrays, or a NumPy array), shared by the
/// surfaces built from it.
struct Field {
    std::shared_ptr<const ScalarField> field;
    std::string input;  ///< the file it was read from ("" otherwise)
    double loadMs = 0.0;
};
Field makeField(ScalarField&& field, const std::string& input);

/// The functions of CfArrays.cpp: xarray's arrays through the NetCDF reader's interpretation.
void bindCfArrays(nb::module_& m);

}  // namespace octrace::python

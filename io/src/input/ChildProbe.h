#pragma once
// Runs a piece of third-party parsing in a child process with a deadline (internal).
//
// HDF5 can loop for hours on a corrupt NetCDF-4 file while libnetcdf opens it (docs/dev/
// fuzzing.md, "HDF5 hangs"): nothing octrace could check beforehand reveals it, and a thread
// stuck inside HDF5 cannot be stopped. So the part that can hang runs first in a forked child;
// only when the child finishes in time does the caller do the same work itself.
#include <functional>
#include <string>

namespace octrace::io::detail {

/// Seconds a NetCDF-4 (HDF5) file's metadata may take to open before it is refused:
/// OCTRACE_HDF5_OPEN_SECONDS when set to a positive number, otherwise 60.
double hdf5OpenDeadline();

/// Forks; the child (its stderr on /dev/null) runs `probe` and exits with a status of its own for "returned" and for
/// "threw". Returns when the child has exited with one of those: the caller then runs the real
/// work and meets the real error, if any. Throws FileError naming `path` and `what` when the
/// child is still running after `seconds` (it is killed), died from a signal, or exited with
/// any other status (a library or, in an instrumented build, a sanitizer ended it). Logs once,
/// after two seconds, that it is still waiting. When fork fails the probe is skipped (logged).
void probeInChild(const std::string& path, const std::string& what, double seconds,
                  const std::function<void()>& probe);

}  // namespace octrace::io::detail

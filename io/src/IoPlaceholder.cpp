// Replaced by the readers and writers.
namespace octrace::io { int ioVersion() { return 1; } }

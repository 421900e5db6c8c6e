using LaserEngrave.Core.Logging;

namespace LaserEngrave.Machines.Runs;

/// <summary>Where a run's log goes: the writer the session writes it with, and the check that the folder takes a file before the run.</summary>
/// <param name="Writer">Writes the record and its summary once the run ends.</param>
/// <param name="CheckWritable">Throws <see cref="RunLogException"/> when the folder cannot take the log (read-only, full).</param>
public sealed record RunLog(IRunLogWriter Writer, Action CheckWritable);

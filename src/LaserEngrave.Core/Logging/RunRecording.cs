namespace LaserEngrave.Core.Logging;

/// <summary>The flight recorder of a run on real ports: every byte in and out with its time, in a file beside the log.</summary>
/// <param name="File">The recording's file name, in the log's folder (JSON lines; see docs/run-log.md).</param>
/// <param name="Events">Writes and reads recorded.</param>
/// <param name="Truncated">True when the file reached its cap and the rest of the run was not recorded.</param>
public sealed record RunRecording(string File, long Events, bool Truncated);

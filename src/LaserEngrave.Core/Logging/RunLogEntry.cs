namespace LaserEngrave.Core.Logging;

/// <summary>One file of a log folder: its record, or the one-line reason it could not be read.</summary>
public sealed record RunLogEntry(string Path, RunRecord? Record, string? Error);

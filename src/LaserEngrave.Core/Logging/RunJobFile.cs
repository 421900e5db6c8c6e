namespace LaserEngrave.Core.Logging;

/// <summary>The job file of a run of layers (`engrave --job`): where it was and its SHA-256, so a resume can refuse a changed job.</summary>
public sealed record RunJobFile(string Path, string Sha256);

namespace LaserEngrave.Core.Logging;

/// <summary>The two files a run's log was written to: the JSON record and the text summary beside it.</summary>
public sealed record RunLogFiles(string JsonPath, string TextPath);

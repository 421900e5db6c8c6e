using LaserEngrave.Core.Logging;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A run log that keeps its records in memory (or fails to write, as a full disk would).</summary>
internal sealed class RecordingLog : IRunLogWriter
{
    public List<RunRecord> Records { get; } = [];

    public bool Fail { get; init; }

    public RunLogFiles Write(RunRecord record)
    {
        Records.Add(record);
        return Fail ? throw new RunLogException("/logs: the disk is full") : new RunLogFiles("run.json", "run.txt");
    }
}

namespace LaserEngrave.Core.Logging;

/// <summary>Where a sweep's log goes: a <see cref="RunLogStore"/> folder, or a test's memory.</summary>
public interface ISweepLogWriter
{
    /// <summary>Writes the sweep's record and its text summary; throws <see cref="RunLogException"/> when they cannot be written.</summary>
    RunLogFiles WriteSweep(SweepRecord record);
}

namespace LaserEngrave.Core.Logging;

/// <summary>Where a run's log goes: a <see cref="RunLogStore"/> folder, or what a front end puts in front of one.</summary>
public interface IRunLogWriter
{
    /// <summary>Writes the record and its text summary; throws <see cref="RunLogException"/> when they cannot be written.</summary>
    RunLogFiles Write(RunRecord record);
}

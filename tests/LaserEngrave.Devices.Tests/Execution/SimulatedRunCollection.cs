namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Runs in virtual time one at a time: the clock's holds lapse after a little wall-clock time, so a starved CPU can let a timeout fire early.</summary>
[CollectionDefinition(Name, DisableParallelization = true)]
public sealed class SimulatedRunCollection
{
    public const string Name = "simulated runs";
}

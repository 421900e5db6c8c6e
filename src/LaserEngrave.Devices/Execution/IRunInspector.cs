using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Devices.Execution;

/// <summary>Looks at what a run did to the sample, for the log; only the simulator can (it records every pulse).</summary>
public interface IRunInspector
{
    /// <summary>What was burned against <paramref name="job"/>'s mask, after every pass has ended.</summary>
    RunSimulation Inspect(PreparedJob job);
}

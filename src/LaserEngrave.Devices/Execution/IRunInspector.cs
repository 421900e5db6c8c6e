using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Devices.Execution;

/// <summary>Looks at what a run did to the sample, for the log; only the simulator can (it records every pulse).</summary>
public interface IRunInspector
{
    /// <summary>Starts looking: what happened before (an earlier run on the same machine) does not count.</summary>
    void Begin();

    /// <summary>What was burned against <paramref name="job"/>'s mask since <see cref="Begin"/>, after every pass has ended.</summary>
    RunSimulation Inspect(PreparedJob job);

    /// <summary>What was burned against <paramref name="drawing"/>'s paths since <see cref="Begin"/>, after every pass has ended.</summary>
    RunSimulation InspectDrawing(PreparedDrawing drawing);
}

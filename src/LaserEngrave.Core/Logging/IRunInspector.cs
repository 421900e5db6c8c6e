using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Logging;

/// <summary>Looks at what a run did to the sample, for the log; only the simulator can (it records every pulse).</summary>
public interface IRunInspector
{
    /// <summary>Starts looking: what happened before (an earlier run on the same machine) does not count.</summary>
    void Begin();

    /// <summary>What was burned against <paramref name="job"/>'s mask since <see cref="Begin"/>, after every pass has ended.</summary>
    /// <param name="job">The job.</param>
    /// <param name="resumedFrom">The stop point the run continued from: what the stopped run burned before it is then neither expected nor missing (<see cref="ResumedBurn"/>).</param>
    RunSimulation Inspect(PreparedJob job, RunStopPoint? resumedFrom = null);

    /// <summary>What was burned against <paramref name="drawing"/>'s paths since <see cref="Begin"/>, after every pass has ended.</summary>
    RunSimulation InspectDrawing(PreparedDrawing drawing);
}

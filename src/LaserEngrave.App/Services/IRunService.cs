using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Runs an engraving session on its machine, reporting progress; cancelling aborts it with the laser switched off first.</summary>
/// <remarks>The seam the view-model's tests fake: the run itself is the Machines use case (<see cref="Machines.Runs.EngraveRun"/>) every front end shares.</remarks>
public interface IRunService
{
    /// <summary>Runs every pass, checks the burn on the simulator, writes the log; faults and refusals are in the result, never thrown.</summary>
    Task<EngraveResult> RunAsync(EngraveSession session, IProgress<EngraveProgress> progress, CancellationToken cancellationToken);
}

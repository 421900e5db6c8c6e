using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Executes a planned job on a machine, reporting progress; cancelling aborts it with the laser switched off first.</summary>
public interface IRunService
{
    /// <summary>Runs every pass; returns the last pass's result (completed, aborted or failed: faults do not throw) with times, estimate and laser-on added up over the passes run.</summary>
    /// <exception cref="PreflightException">The machine refused the job before anything moved under the laser.</exception>
    Task<RunResult> RunAsync(RunRequest request, IProgress<RunProgress> progress, CancellationToken cancellationToken);
}

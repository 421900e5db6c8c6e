using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Executes a planned job on a machine, reporting progress; cancelling aborts it with the laser switched off first.</summary>
public interface IRunService
{
    /// <summary>Runs every pass; returns the executor's result of the last pass run (completed, aborted or failed: faults do not throw).</summary>
    /// <exception cref="PreflightException">The machine refused the job before anything moved under the laser.</exception>
    Task<RunResult> RunAsync(RunRequest request, IProgress<RunProgress> progress, CancellationToken cancellationToken);
}

namespace LaserEngrave.App.Services;

/// <summary>Executes a planned job on a machine, reporting progress; cancelling aborts it with the laser switched off first.</summary>
public interface IRunService
{
    /// <summary>Runs every pass; throws <see cref="OperationCanceledException"/> when aborted and device errors on faults, the laser off in both cases.</summary>
    Task RunAsync(RunRequest request, IProgress<RunProgress> progress, CancellationToken cancellationToken);
}

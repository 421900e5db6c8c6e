using CommunityToolkit.Mvvm.Messaging;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Runs an <see cref="EngraveSession"/> on its machine (the same use case as the command line's engrave).</summary>
public sealed class EngraveRunService : IRunService
{
    public async Task<EngraveResult> RunAsync(EngraveSession session, IProgress<EngraveProgress> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(session);
        ArgumentNullException.ThrowIfNull(progress);
        var result = await session.RunAsync(progress, cancellationToken).ConfigureAwait(false);
        if (session.Options.JobFile is { } jobFile)
        {
            try
            {
                // A job of marks advances the sample counter when, and only when, its run completed (docs/marking.md).
                if (Core.Marks.MarkManifest.AfterRun(jobFile, result.Record.Outcome, result.Record.JobFile?.Marks) is not null)
                {
                    WeakReferenceMessenger.Default.Send(new ViewModels.MarkViewModel.CounterAdvancedMessage());
                }
            }
            catch (Exception ex) when (ex is Core.Marks.MarkException or IOException or UnauthorizedAccessException)
            {
                // The run is over and logged; the Mark panel shows the counter's number, read again before the next job.
            }
        }

        return result;
    }
}

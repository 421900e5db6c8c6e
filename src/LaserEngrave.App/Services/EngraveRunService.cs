using CommunityToolkit.Mvvm.Messaging;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Machines.Runs;

namespace LaserEngrave.App.Services;

/// <summary>Runs an <see cref="EngraveSession"/> of an <see cref="EngraveRun"/> to its end (the same use case as the command line's engrave).</summary>
public sealed class EngraveRunService : IRunService
{
    public async Task<EngraveResult> RunAsync(EngraveSession session, IProgress<EngraveProgress> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(session);
        ArgumentNullException.ThrowIfNull(progress);
        var end = await EngraveRun.RunAsync(session, progress, cancellationToken).ConfigureAwait(false);

        // The Mark panel shows the counter's number: read again once a completed run of marks advanced it (a counter
        // that could not be written is read again before the next job all the same).
        if (end.NextMarkNumber is not null)
        {
            WeakReferenceMessenger.Default.Send(new ViewModels.MarkViewModel.CounterAdvancedMessage());
        }

        return end.Result;
    }
}

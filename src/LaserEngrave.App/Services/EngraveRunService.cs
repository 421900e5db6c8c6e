using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Runs an <see cref="EngraveSession"/> on its machine (the same use case as the command line's engrave).</summary>
public sealed class EngraveRunService : IRunService
{
    public Task<EngraveResult> RunAsync(EngraveSession session, IProgress<EngraveProgress> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(session);
        ArgumentNullException.ThrowIfNull(progress);
        return session.RunAsync(progress, cancellationToken);
    }
}

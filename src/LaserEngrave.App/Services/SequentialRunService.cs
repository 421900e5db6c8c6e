using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.Services;

/// <summary>
/// Runs a plan move by move: laser on only for burn moves, off before anything else moves, speeds set per move kind.
/// </summary>
/// <remarks>
/// The app's own executor until the executor of branch `execution` (Devices/Execution) is merged; it keeps the gate's
/// watchdog fed during long burns, and on abort or fault switches the laser off before it stops the axes.
/// </remarks>
public sealed class SequentialRunService : IRunService
{
    private static readonly TimeSpan KeepAlivePeriod = TimeSpan.FromMilliseconds(300);

    public async Task RunAsync(RunRequest request, IProgress<RunProgress> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(request);
        ArgumentNullException.ThrowIfNull(progress);
        var job = request.Job;
        var stage = request.Stage;
        var gate = request.Gate;
        var process = job.Spec.Process;
        var microstepUm = job.Spec.Profile.X.MicrostepUm;
        var strategy = job.Plan.Options.Strategy;
        var moves = job.Plan.Moves().ToList();
        var rows = job.Plan.Rows().Select(r => r.FirstMoveIndex + r.MoveCount).ToArray();
        var laserOn = false;
        try
        {
            await gate.OffAsync(cancellationToken).ConfigureAwait(false);
            var acceleration = StageUnits.AccelerationData(process.AccelerationMmPerS2, microstepUm);
            await stage.X.SetAccelerationAsync(acceleration, cancellationToken).ConfigureAwait(false);
            await stage.Y.SetAccelerationAsync(acceleration, cancellationToken).ConfigureAwait(false);
            int? xSpeed = null;
            int? ySpeed = null;
            for (var pass = 1; pass <= Math.Max(1, request.Passes); pass++)
            {
                var rowsDone = 0;
                for (var i = 0; i < moves.Count; i++)
                {
                    await request.Pause.WaitAsync(cancellationToken).ConfigureAwait(false);
                    var move = moves[i];
                    var speed = StageUnits.SpeedData(process.SpeedMmPerS(move.Kind, strategy), microstepUm);
                    if (xSpeed != speed && move.X1 != move.X0)
                    {
                        await stage.X.SetTargetSpeedAsync(speed, cancellationToken).ConfigureAwait(false);
                        xSpeed = speed;
                    }

                    if (ySpeed != speed && move.Y1 != move.Y0)
                    {
                        await stage.Y.SetTargetSpeedAsync(speed, cancellationToken).ConfigureAwait(false);
                        ySpeed = speed;
                    }

                    if (move.Kind == MoveKind.Burn)
                    {
                        await gate.SetFrequencyAsync(process.LaserFrequencyWholeHz, cancellationToken).ConfigureAwait(false);
                        laserOn = true;
                        progress.Report(Progress(i, move.X0, move.Y0, true));
                        await BurnAsync(stage.X, gate, move.X1, cancellationToken).ConfigureAwait(false);
                        await gate.OffAsync(cancellationToken).ConfigureAwait(false);
                        laserOn = false;
                    }
                    else
                    {
                        // Both axes at once for a diagonal travel; the laser is already off.
                        var x = move.X1 != move.X0 ? stage.X.MoveAbsoluteAsync(move.X1, cancellationToken) : Task.FromResult(move.X1);
                        var y = move.Y1 != move.Y0 ? stage.Y.MoveAbsoluteAsync(move.Y1, cancellationToken) : Task.FromResult(move.Y1);
                        await Task.WhenAll(x, y).ConfigureAwait(false);
                    }

                    while (rowsDone < rows.Length && rows[rowsDone] <= i + 1)
                    {
                        rowsDone++;
                    }

                    progress.Report(Progress(i + 1, move.X1, move.Y1, false));

                    RunProgress Progress(long done, long x, long y, bool on) =>
                        new(done, moves.Count, rowsDone, rows.Length, pass, x, y, on);
                }
            }
        }
        finally
        {
            // The laser goes off first whatever happened; then the axes stop. Neither may be cancelled.
            await SafelyAsync(() => gate.OffAsync(CancellationToken.None)).ConfigureAwait(false);
            if (cancellationToken.IsCancellationRequested || laserOn)
            {
                await SafelyAsync(() => stage.X.StopAsync(CancellationToken.None)).ConfigureAwait(false);
                await SafelyAsync(() => stage.Y.StopAsync(CancellationToken.None)).ConfigureAwait(false);
            }
        }
    }

    private static async Task BurnAsync(IStageAxis x, ILaserGate gate, long target, CancellationToken cancellationToken)
    {
        var move = x.MoveAbsoluteAsync(target, cancellationToken);
        while (await Task.WhenAny(move, Task.Delay(KeepAlivePeriod, cancellationToken)).ConfigureAwait(false) != move)
        {
            await gate.KeepAliveAsync(cancellationToken).ConfigureAwait(false);
        }

        await move.ConfigureAwait(false);
    }

    private static async Task SafelyAsync(Func<Task> action)
    {
        try
        {
            await action().ConfigureAwait(false);
        }
        catch (Exception ex) when (ex is DeviceException or OperationCanceledException or ObjectDisposedException or InvalidOperationException)
        {
            // Already failing or aborting: the first error is the one the user sees.
        }
    }
}

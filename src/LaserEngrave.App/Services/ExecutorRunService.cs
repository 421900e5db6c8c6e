using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>Runs a job with the Devices <see cref="RunExecutor"/> (preflight, keepalive, pause, laser-off-first abort), one executor per pass.</summary>
public sealed class ExecutorRunService : IRunService
{
    public async Task<RunResult> RunAsync(RunRequest request, IProgress<RunProgress> progress, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(request);
        ArgumentNullException.ThrowIfNull(progress);
        var movesTotal = request.Job.Statistics.Moves;
        RunResult? last = null;
        // Continuing a stopped run finishes the pass that stopped, and only that.
        var passes = request.ResumeFrom is null ? Math.Max(1, request.Passes) : 1;
        for (var pass = 1; pass <= passes; pass++)
        {
            var options = new RunOptions { ResumeFrom = pass == 1 ? request.ResumeFrom : null };
            var executor = new RunExecutor(request.Stage, request.Gate, request.Job, request.TimeProvider, options);
            var movesDone = 0L;
            var latest = executor.Progress;
            var currentPass = pass;
            void Report() => progress.Report(new RunProgress(
                Interlocked.Read(ref movesDone), movesTotal, latest.RowsDone, latest.RowsTotal, currentPass, latest.XMicrosteps, latest.YMicrosteps, latest.LaserOn, latest.State.ToString().ToLowerInvariant(), latest.Remaining.TotalSeconds));
            executor.MoveCompleted += (_, e) => Interlocked.Exchange(ref movesDone, e.MoveIndex + 1);
            executor.ProgressChanged += (_, p) =>
            {
                latest = p;
                Report();
            };
            void OnPause(object? sender, bool paused)
            {
                if (paused)
                {
                    executor.Pause();
                }
                else
                {
                    executor.Resume();
                }
            }

            request.Pause.Changed += OnPause;
            RunResult result;
            try
            {
                if (request.Pause.IsPaused)
                {
                    executor.Pause();
                }

                result = await TaskRunner.For(request.TimeProvider).Run(() => executor.RunAsync(cancellationToken));
            }
            finally
            {
                request.Pause.Changed -= OnPause;
            }

            Report();
            // The log speaks for the whole job: times and laser-on add up over the passes, the counts are the last pass's.
            last = last is null ? result : result with
            {
                StartedAt = last.StartedAt,
                EngravingDuration = last.EngravingDuration + result.EngravingDuration,
                EstimatedSeconds = last.EstimatedSeconds + result.EstimatedSeconds,
                LaserOnSeconds = last.LaserOnSeconds + result.LaserOnSeconds,
            };
            if (result.Outcome != RunOutcome.Completed)
            {
                break;
            }
        }

        return last!;
    }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>What a motion strategy asks of the run it moves the stage for: the shared moves, the laser, the counts.</summary>
internal interface IRunMotion
{
    RunOptions Options { get; }

    TimeProvider TimeProvider { get; }

    ILaserGate Gate { get; }

    /// <summary>The laser: its lock, its state.</summary>
    LaserSafety Laser { get; }

    /// <summary>The counts of moves, rows and runs done, and the estimate.</summary>
    RunAccounting Accounting { get; }

    ProcessSettings Process { get; }

    MachineProfile Profile { get; }

    /// <summary>Whether preflight homed (the estimate's preparation homes from the far end).</summary>
    bool Homed { get; }

    /// <summary>Where the stage stands, microsteps.</summary>
    (long X, long Y) Position { get; }

    /// <summary>Where the estimate starts counting: the first move and its row, then the acceleration and travel speed set.</summary>
    Task BeginEngravingAsync(long firstIndex, int row, CancellationToken token);

    /// <summary>Moves both axes to (x, y) at <paramref name="speedData"/>, waiting for both.</summary>
    Task MoveToAsync(long x, long y, int speedData, CancellationToken token);

    /// <summary>Holds a paused run here, the laser off, until it is resumed or aborted.</summary>
    Task PauseIfAskedAsync(CancellationToken token);

    /// <summary>A move of the plan completed: counted, then reported.</summary>
    void Completed(Move move, long index);

    void ThrowIfAborted();

    /// <summary>Time spent that is not engraving (reaching the first position), taken off the engraving's clock.</summary>
    void NotEngraving(TimeSpan spent);
}

/// <summary>
/// Dot mode: stop at each dot, fire exactly N pulses with the gate's burst, move on only once the burst has surely ended.
/// </summary>
/// <remarks>
/// The steps are the plan's <see cref="DotProgram"/>, timed as <see cref="DotTiming"/> models and added up by
/// <see cref="DotModeEstimate"/> (docs/process.md, "Dot mode"). The laser fires only while the stage stands: a burst is
/// sent after every axis has reported its arrival (and the settle time), and the next move only after the burst's end.
/// Each dot is a <see cref="MoveKind.Burn"/> of zero length in the run's completed moves and in the counters (runs =
/// dots); a stop point's index is the first dot not fired.
/// </remarks>
internal sealed class DotMotion(IRunMotion run, DotProgram program)
{
    /// <summary>The motion from the resume point on; for a resumed run the dots fired before it, counted, and the estimate of what is left.</summary>
    /// <exception cref="PreflightException">The resume point is not in this job's plan.</exception>
    public Func<CancellationToken, Task> Prepare()
    {
        var firstIndex = SkipDotsDone();
        run.Accounting.EstimatePreparation = EstimatePreparation(firstIndex);
        return token => ExecuteAsync(firstIndex, token);
    }

    private async Task ExecuteAsync(long firstIndex, CancellationToken token)
    {
        var timing = program.Timing;

        // Every move between dots is a travel.
        await run.BeginEngravingAsync(firstIndex, run.Options.ResumeFrom?.Row ?? 0, token);
        var settle = TimeSpan.FromSeconds(timing.SettleSeconds);
        var index = firstIndex;
        var first = true;
        foreach (var step in program.Steps(firstIndex))
        {
            run.Accounting.Executing(index, step.Row);

            await run.PauseIfAskedAsync(token);
            if (first)
            {
                // Reaching the first dot (or the resume point's) is not part of the estimate.
                var positioning = run.TimeProvider.GetTimestamp();
                await run.MoveToAsync(step.X, step.Y, step.SpeedData, token);
                run.NotEngraving(run.TimeProvider.GetElapsedTime(positioning));
                first = false;
            }
            else
            {
                await run.MoveToAsync(step.X, step.Y, step.SpeedData, token);
            }

            await PreciseDelay.DelayAsync(run.TimeProvider, settle, token);
            await FireAsync(step, timing, token);
            run.Completed(new Move(MoveKind.Burn, step.X, step.Y, step.X, step.Y, step.Row), index);
            index++;
        }

        run.Accounting.Ended(index, program.Plan.Mask.Height);
    }

    /// <summary>The step's burst at the stage's standing position; returns once the laser is surely off again.</summary>
    private async Task FireAsync(DotStep step, DotTiming timing, CancellationToken token)
    {
        var laser = run.Laser;
        Task burst;
        await laser.Lock.WaitAsync();
        try
        {
            // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after the burst.
            run.ThrowIfAborted();
            laser.MarkOn(run.TimeProvider.GetTimestamp());

            // Not cancelled: a reply arriving after a cancelled command would be taken for the next one's. Started under
            // the lock (written before an abort's switch-off, or dropped by the gate), awaited outside it: an abort's
            // switch-off never waits behind a gate that does not answer.
            burst = run.Gate.BurstAsync(step.Pulses, step.FrequencyHz, CancellationToken.None);
        }
        finally
        {
            laser.Lock.Release();
        }

        await burst;

        // The gate answers as the burst starts; nothing moves before it has surely ended. An abort meanwhile switches the laser off.
        await PreciseDelay.DelayAsync(run.TimeProvider, TimeSpan.FromSeconds(timing.AfterAckSeconds), token);
        laser.MarkBurstOver(timing.BurstSeconds);
    }

    /// <summary>Preflight's share of the estimate before the first dot: the exchanges, homing if it homed, and the travel to the dot.</summary>
    private double EstimatePreparation(long firstIndex) =>
        program.Steps(firstIndex).Take(1).ToList() is [var first]
            ? TimedSwitching.For(run.Process, run.Profile, program.MicrostepUm).PreparationSeconds(first.X, first.Y, run.Homed, from: run.Position)
            : 0;

    private long SkipDotsDone()
    {
        var estimate = program.Plan.Estimate;
        run.Accounting.EstimateTotal = estimate.TotalSeconds;
        if (run.Options.ResumeFrom is not { } resume)
        {
            return 0;
        }

        var start = resume.MoveIndex;
        if (start < 0 || start > estimate.Dots)
        {
            throw new PreflightException($"the resume point (row {resume.Row}, dot {resume.MoveIndex}) is not in this job's plan of {estimate.Dots} dots");
        }

        // The dots before, counted as the run counts them; their time as the estimate counts it (the start settings included).
        foreach (var step in program.Steps().TakeWhile(s => s.Index < start))
        {
            run.Accounting.CountDone(MoveKind.Burn, step.Row);
        }

        run.Accounting.EstimateBefore = program.SecondsBefore(start);
        return start;
    }
}

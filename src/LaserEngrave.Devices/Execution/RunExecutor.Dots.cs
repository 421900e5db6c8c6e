using LaserEngrave.Core.Planning;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Dot mode: stop at each dot, fire exactly N pulses with the gate's burst, move on only once the burst has surely ended.</summary>
/// <remarks>
/// The steps are the plan's <see cref="DotProgram"/>, timed as <see cref="DotTiming"/> models and added up by
/// <see cref="DotModeEstimate"/> (docs/process.md, "Dot mode"). The laser fires only while the stage stands: a burst is sent after every axis has reported its arrival (and
/// the settle time), and the next move only after the burst's end. Each dot is a <see cref="MoveKind.Burn"/> of zero
/// length in <see cref="MoveCompleted"/> and in the counters (runs = dots); a stop point's index is the first dot not fired.
/// </remarks>
public sealed partial class RunExecutor
{
    private async Task ExecuteDotsAsync(DotProgram program, long firstIndex, CancellationToken token)
    {
        var timing = program.Timing;
        // Every move between dots is a travel.
        await BeginEngravingAsync(firstIndex, Options.ResumeFrom?.Row ?? 0, token);
        var settle = TimeSpan.FromSeconds(timing.SettleSeconds);
        var index = firstIndex;
        var first = true;
        foreach (var step in program.Steps(firstIndex))
        {
            _accounting.Executing(index, step.Row);

            await PauseIfAskedAsync(token);
            if (first)
            {
                // Reaching the first dot (or the resume point's) is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                await MoveToAsync(step.X, step.Y, step.SpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
                first = false;
            }
            else
            {
                await MoveToAsync(step.X, step.Y, step.SpeedData, token);
            }

            await PreciseDelay.DelayAsync(TimeProvider, settle, token);
            await FireDotAsync(step, timing, token);
            Completed(new Move(MoveKind.Burn, step.X, step.Y, step.X, step.Y, step.Row), index);
            index++;
        }

        _accounting.Ended(index, program.Plan.Mask.Height);
    }

    /// <summary>The step's burst at the stage's standing position; returns once the laser is surely off again.</summary>
    private async Task FireDotAsync(DotStep step, DotTiming timing, CancellationToken token)
    {
        Task burst;
        await _laser.Lock.WaitAsync();
        try
        {
            // Inside the lock: an abort's switch-off is either already sent (and we stop here) or comes after the burst.
            ThrowIfAborted();
            _laser.MarkOn(TimeProvider.GetTimestamp());

            // Not cancelled: a reply arriving after a cancelled command would be taken for the next one's. Started under
            // the lock (written before an abort's switch-off, or dropped by the gate), awaited outside it: an abort's
            // switch-off never waits behind a gate that does not answer.
            burst = Gate.BurstAsync(step.Pulses, step.FrequencyHz, CancellationToken.None);
        }
        finally
        {
            _laser.Lock.Release();
        }

        await burst;

        // The gate answers as the burst starts; nothing moves before it has surely ended. An abort meanwhile switches the laser off.
        await PreciseDelay.DelayAsync(TimeProvider, TimeSpan.FromSeconds(timing.AfterAckSeconds), token);
        _laser.MarkBurstOver(timing.BurstSeconds);
    }

    /// <summary>Preflight's share of the estimate before the first dot: the exchanges, homing if it homed, and the travel to the dot.</summary>
    private double EstimateDotsPreparation(DotProgram program, long firstIndex) =>
        program.Steps(firstIndex).Take(1).ToList() is [var first]
            ? TimedSwitching.For(_process, _profile, program.MicrostepUm).PreparationSeconds(first.X, first.Y, _homed, from: (_x, _y))
            : 0;

    /// <summary>A dot job's motion from the resume point on; for a resumed run the dots fired before it, counted, and the estimate of what is left.</summary>
    private Func<CancellationToken, Task> PrepareDots(DotProgram program)
    {
        var firstIndex = SkipDotsDone(program);
        _accounting.EstimatePreparation = EstimateDotsPreparation(program, firstIndex);
        return token => ExecuteDotsAsync(program, firstIndex, token);
    }

    private long SkipDotsDone(DotProgram program)
    {
        var estimate = program.Plan.Estimate;
        _accounting.EstimateTotal = estimate.TotalSeconds;
        if (Options.ResumeFrom is not { } resume)
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
            _accounting.CountDone(MoveKind.Burn, step.Row);
        }

        _accounting.EstimateBefore = program.SecondsBefore(start);
        return start;
    }
}

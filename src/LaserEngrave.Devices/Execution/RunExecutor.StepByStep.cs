using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>The step-by-step motion (a paper plan, or one without a timing model), the positioning before the first move of every kind of plan, and the moves every strategy shares.</summary>
public sealed partial class RunExecutor
{
    // The burn run of a step-by-step raster run whose switch-on was sent last (under the engine's lock): a stop in it names its cut pixel.
    private (Move Move, long Index)? _litMove;

    /// <summary>
    /// Where every execution starts, and where its estimate starts counting: the stop point at the first move (and a row
    /// it is in), then the acceleration and the travel speed set on both axes.
    /// </summary>
    private async Task BeginEngravingAsync(long firstIndex, int row, CancellationToken token)
    {
        _accounting.At(firstIndex, row);

        _engravingStart = TimeProvider.GetTimestamp();
        _engravingStarted = true;
        foreach (var axis in new[] { Stage.X, Stage.Y })
        {
            await axis.SetAccelerationAsync(_program.Motion.AccelerationData, token);
            await axis.SetTargetSpeedAsync(_program.Motion.TravelSpeedData, token);
        }

        (_xSpeedData, _ySpeedData) = (_program.Motion.TravelSpeedData, _program.Motion.TravelSpeedData);
    }

    private async Task ExecuteAsync(RasterProgram program, IEnumerable<RasterStep> steps, long firstIndex, CancellationToken token)
    {
        await BeginEngravingAsync(firstIndex, Options.ResumeFrom?.Row ?? 0, token);
        var index = firstIndex;
        var first = true;
        foreach (var step in steps)
        {
            var (move, moveIndex) = (step.Move.Move, step.Move.MoveIndex);
            if (first)
            {
                // Reaching the plan's (or the resume point's) first position is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                await MoveToAsync(move.X0, move.Y0, program.Motion.TravelSpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
                first = false;
            }

            _accounting.Executing(moveIndex, move.Row, move);

            await PauseIfAskedAsync(token);
            await ExecuteMoveAsync(step.Move, token);
            Completed(move, moveIndex);
            index = moveIndex + 1;
        }

        _accounting.Ended(index, program.Plan.Mask.Height);
    }

    /// <summary>
    /// A raster's motion: its steps by the run's own timing model (wider latencies when preflight found them), from the
    /// resume point on; for a resumed run also the counters and estimates of what was done before. The estimate is the
    /// plan's program's (<paramref name="planned"/>).
    /// </summary>
    /// <exception cref="PreflightException">The resume point is not in this job's plan.</exception>
    private Func<CancellationToken, Task> Prepare(RasterProgram planned)
    {
        var program = planned.Timing == _timing ? planned : planned.Retimed(_timing);
        _accounting.Estimator = program.Timing is null ? new PlanEstimator(planned) : null;
        IEnumerable<RasterStep> steps;
        long firstIndex = 0;
        if (Options.ResumeFrom is not { } stop)
        {
            _accounting.EstimateTotal = Part.EngravingSeconds;
            steps = program.Steps();
        }
        else
        {
            RasterResume resume;
            try
            {
                resume = program.ResumeAt(stop, _resumeX);
            }
            catch (PlanException ex)
            {
                throw new PreflightException(ex.Message);
            }

            _accounting.DoneBefore(resume.RowsBefore, resume.RunsBefore, resume.LastRowBefore);
            var (before, remaining) = planned.EstimateResumed(resume);
            _accounting.EstimateBefore = before;
            _accounting.EstimateTotal = before + remaining;
            steps = program.Steps(resume);
            firstIndex = resume.FirstMoveIndex;
        }

        _accounting.EstimatePreparation = EstimatePreparation(planned, steps);
        return program.Timing is { } timing
            ? token => ExecuteTimedAsync(program, steps, firstIndex, timing, token)
            : token => ExecuteAsync(program, steps, firstIndex, token);
    }

    /// <summary>The estimate of what preflight did and the travel to the first move will take, as the plan's figure is made.</summary>
    private double EstimatePreparation(RasterProgram planned, IEnumerable<RasterStep> steps) =>
        planned.Timing is { } timing && steps.Take(1).ToList() is [var first]
            ? timing.PreparationSeconds(first.FirstMove.X0, first.FirstMove.Y0, _homed, from: (_x, _y))
            : 0;

    private async Task ExecuteMoveAsync(MoveStep step, CancellationToken token)
    {
        var move = step.Move;
        var burn = step.LaserOn;

        // Off before anything else, so the laser never stands still on while speeds are set.
        if (!burn && _laser.On)
        {
            await _laser.SwitchAsync(on: false);
        }

        // Speeds before switching on, for the same reason (docs/simulator.md: dwell).
        var speedData = step.SpeedData;
        await SetSpeedsAsync(move.LengthX != 0, move.LengthY != 0, speedData, token);
        if (burn)
        {
            lock (_lock)
            {
                // From here the laser may fire over this run (a switch-on carried out but never acknowledged too).
                _litMove = (move, step.MoveIndex);
            }
        }

        if (burn && !_laser.On)
        {
            await _laser.SwitchAsync(on: true);
        }

        if (burn)
        {
            // No keepalive in the last moments of the run: a switch-off queued behind one would leave the laser standing on.
            var motion = new TrapezoidProfile(move.LengthX, StageUnits.SpeedMicrostepsPerS(speedData), StageUnits.AccelerationMicrostepsPerS2(_program.Motion.AccelerationData));
            var quietAfterSeconds = Math.Max(0, motion.Duration - KeepAliveQuietSeconds);
            _laser.KeepAlive!.QuietFrom = TimeProvider.GetTimestamp() + (long)(quietAfterSeconds * TimeProvider.TimestampFrequency);
        }

        await MoveAxesAsync(move.LengthX != 0 ? step.X : null, move.LengthY != 0 ? step.Y : null, token);
    }

    /// <summary>
    /// The stop point's cut pixel when a step-by-step raster run stopped in a burn run whose switch-on was sent: the run
    /// is burned again from its start on resuming, so every pixel from its start to where X stopped (the laser went off
    /// before the stop) may get part of their dose twice, and the cut pixel names the last of them; the run's last pixel
    /// when X could not say where it stopped. Caller holds the lock.
    /// </summary>
    private RunStopPoint StepCut(RunStopPoint stop, RasterPlan plan)
    {
        if (_litMove is not { } lit || lit.Index != stop.MoveIndex || lit.Move.X0 == lit.Move.X1)
        {
            return stop;
        }

        var move = lit.Move;
        var x = _stoppedAtKnownPosition ? _x : move.X1;

        // Inside the run: a stop short of its first edge is its first pixel, one past its last edge its last pixel.
        var inside = Math.Clamp(x, Math.Min(move.X0, move.X1) + 1, Math.Max(move.X0, move.X1) - 1);
        return stop with { CutPixel = new PixelIndex(plan.ColumnAt(move, inside), move.Row) };
    }

    /// <summary>A travel to (<paramref name="x"/>, <paramref name="y"/>); an axis already there is left alone unless <paramref name="unsure"/> says its position is the model's, not a reply's.</summary>
    private async Task MoveToAsync(long x, long y, int speedData, CancellationToken token, (bool X, bool Y) unsure = default)
    {
        if (_laser.On)
        {
            await _laser.SwitchAsync(on: false);
        }

        bool moveX = x != _x || unsure.X, moveY = y != _y || unsure.Y;
        await SetSpeedsAsync(moveX, moveY, speedData, token);
        await MoveAxesAsync(moveX ? x : null, moveY ? y : null, token);
    }

    private async Task SetSpeedsAsync(bool x, bool y, int speedData, CancellationToken token)
    {
        if (x && _xSpeedData != speedData)
        {
            await Stage.X.SetTargetSpeedAsync(speedData, token);
            _xSpeedData = speedData;
        }

        if (y && _ySpeedData != speedData)
        {
            await Stage.Y.SetTargetSpeedAsync(speedData, token);
            _ySpeedData = speedData;
        }
    }

    private async Task MoveAxesAsync(long? x, long? y, CancellationToken token)
    {
        ThrowIfAborted();
        var xMove = x is { } toX ? Stage.X.MoveAbsoluteAsync(toX, token) : null;
        var yMove = y is { } toY ? Stage.Y.MoveAbsoluteAsync(toY, token) : null;
        try
        {
            if (xMove is not null)
            {
                _x = Arrived("X", await xMove, x!.Value);
            }

            if (yMove is not null)
            {
                _y = Arrived("Y", await yMove, y!.Value);
            }
        }
        catch
        {
            // Observe the other axis' move so its failure is not left unobserved.
            foreach (var pending in new[] { xMove, yMove })
            {
                if (pending is not null)
                {
                    _ = pending.ContinueWith(t => t.Exception, CancellationToken.None, TaskContinuationOptions.OnlyOnFaulted, TaskScheduler.Default);
                }
            }

            throw;
        }
    }

    private static long Arrived(string axis, long position, long target) =>
        position == target
            ? position
            : throw new DeviceException($"the {axis} axis reports arriving at {position} instead of {target} microsteps (a garbled reply, or the axis was stopped)");
}

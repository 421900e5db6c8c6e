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
            await axis.SetAccelerationAsync(_accelerationData, token);
            await axis.SetTargetSpeedAsync(_travelSpeedData, token);
        }

        (_xSpeedData, _ySpeedData) = (_travelSpeedData, _travelSpeedData);
    }

    private async Task ExecuteAsync(IEnumerable<Move> moves, long firstIndex, CancellationToken token)
    {
        await BeginEngravingAsync(firstIndex, Options.ResumeFrom?.Row ?? 0, token);
        var index = firstIndex;
        var first = true;
        foreach (var move in moves)
        {
            if (first)
            {
                // Reaching the plan's (or the resume point's) first position is not part of the estimate.
                var positioning = TimeProvider.GetTimestamp();
                await MoveToAsync(move.X0, move.Y0, _travelSpeedData, token);
                _notEngraving += TimeProvider.GetElapsedTime(positioning);
                first = false;
            }

            _accounting.Executing(index, move.Row, move);

            await PauseIfAskedAsync(token);
            await ExecuteMoveAsync(move, token);
            Completed(move, index);
            index++;
        }

        _accounting.Ended(index, Job!.Plan.Mask.Height);
    }

    /// <summary>The moves to execute and the index of the first; for a resumed run also the counters and estimates of what was done before.</summary>
    /// <exception cref="PreflightException">The resume point is not in this job's plan.</exception>
    private (IEnumerable<Move> Moves, long FirstIndex) Prepare()
    {
        var plan = Job!.Plan;
        var microstepUm = plan.Geometry.MicrostepUm;
        var strategy = plan.Options.Strategy;
        _accounting.Estimator = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        if (Options.ResumeFrom is not { } resume)
        {
            _accounting.EstimateTotal = Job.Statistics.EngravingSeconds;
            return (plan.Moves(), 0);
        }

        // A burn run is resumed with its run-up, as it was planned; one cut off midway, from its first pixel not
        // completely burned (the stroke then gets its run-up before that edge).
        var start = resume.MoveIndex;
        long index = 0;
        Move? previous = null;
        Move? trimmed = null;
        foreach (var move in plan.Moves())
        {
            if (index == resume.MoveIndex)
            {
                if (_resumeX is { } x)
                {
                    var dir = Math.Sign(move.X1 - move.X0);
                    if (move.Kind != MoveKind.Burn || (x - move.X0) * dir <= 0 || (move.X1 - x) * dir <= 0)
                    {
                        throw new PreflightException($"the resume point (row {resume.Row}, move {resume.MoveIndex}, X {x}) is not inside a burn run of this job's plan");
                    }

                    trimmed = move with { X0 = x };
                }
                else if (move.Kind == MoveKind.Burn && previous is { Kind: MoveKind.Overscan } runUp && runUp.Row == move.Row)
                {
                    start--;
                }

                break;
            }

            previous = move;
            index++;
        }

        // What was done before the resume point, where its row starts, and the estimate of what is left.
        var before = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        var remaining = new PlanEstimator(_process, strategy, microstepUm, _profile.Gate, plan.Timing);
        long rowStart = -1;
        index = 0;
        foreach (var move in plan.Moves())
        {
            if (rowStart < 0 && move.Row >= resume.Row)
            {
                rowStart = index;
            }

            if (index < start)
            {
                before.Add(move);
                _accounting.CountDone(move.Kind, move.Row);
            }
            else
            {
                remaining.Add(move);
            }

            index++;
        }

        remaining.Finish();
        if (start < 0 || start > index || (start < index && (rowStart < 0 || rowStart > start)))
        {
            throw new PreflightException($"the resume point (row {resume.Row}, move {resume.MoveIndex}) is not in this job's plan of {index} moves");
        }

        _accounting.EstimateBefore = before.ElapsedSeconds - before.StartSeconds;
        _accounting.EstimateTotal = _accounting.EstimateBefore + remaining.ElapsedSeconds;
        if (start == index)
        {
            return ([], index);
        }

        var moves = plan.Moves(resume.Row).Skip(checked((int)(start - rowStart)));
        return (trimmed is { } first ? moves.Skip(1).Prepend(first) : moves, start);
    }

    /// <summary>The estimate of what preflight did and the travel to the first move will take, as the plan's figure is made.</summary>
    private double EstimatePreparation(IEnumerable<Move> moves) =>
        Job?.Plan.Timing is { } timing && moves.Take(1).ToList() is [var first]
            ? timing.PreparationSeconds(first.X0, first.Y0, _homed, from: (_x, _y))
            : 0;

    private async Task ExecuteMoveAsync(Move move, CancellationToken token)
    {
        var burn = move.Kind == MoveKind.Burn;

        // Off before anything else, so the laser never stands still on while speeds are set.
        if (!burn && _laser.On)
        {
            await _laser.SwitchAsync(on: false);
        }

        // Speeds before switching on, for the same reason (docs/simulator.md: dwell).
        var speedData = burn || move.Kind == MoveKind.Overscan ? _burnSpeedData : _travelSpeedData;
        await SetSpeedsAsync(move.LengthX != 0, move.LengthY != 0, speedData, token);
        if (burn && !_laser.On)
        {
            await _laser.SwitchAsync(on: true);
        }

        if (burn)
        {
            // No keepalive in the last moments of the run: a switch-off queued behind one would leave the laser standing on.
            var motion = new TrapezoidProfile(move.LengthX, StageUnits.SpeedMicrostepsPerS(speedData), StageUnits.AccelerationMicrostepsPerS2(_accelerationData));
            var quietAfterSeconds = Math.Max(0, motion.Duration - KeepAliveQuietSeconds);
            _laser.KeepAlive!.QuietFrom = TimeProvider.GetTimestamp() + (long)(quietAfterSeconds * TimeProvider.TimestampFrequency);
        }

        await MoveAxesAsync(move.LengthX != 0 ? move.X1 : null, move.LengthY != 0 ? move.Y1 : null, token);
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

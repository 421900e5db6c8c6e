using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>An axis of the stage, for jogging.</summary>
public enum StageAxisName
{
    X,
    Y,
}

/// <summary>A stage position in whole microsteps.</summary>
public readonly record struct StagePosition(long XMicrosteps, long YMicrosteps);

/// <summary>A test move whose target is unusable (outside the travel, not a number); the message is one line.</summary>
public sealed class TestMoveException : DeviceException
{
    public TestMoveException(string message)
        : base(message)
    {
    }
}

/// <summary>Moves a technician makes before or between runs: jog, go to, home, frame the job, test fire; the laser is always off at the end.</summary>
/// <remarks>
/// Moves run at the process' travel speed and acceleration (set before each operation). Targets are checked against
/// the profile's travel before anything is sent. Waits run on the given <see cref="TimeProvider"/>.
/// </remarks>
public sealed class StageTestMoves
{
    public StageTestMoves(IStage stage, ILaserGate gate, MachineProfile profile, ProcessSettings? process = null, TimeProvider? timeProvider = null)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(profile);
        Stage = stage;
        Gate = gate;
        Profile = profile;
        Process = process ?? ProcessSettings.FromProfile(profile);
        TimeProvider = timeProvider ?? TimeProvider.System;
    }

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    public MachineProfile Profile { get; }

    public ProcessSettings Process { get; }

    public TimeProvider TimeProvider { get; }

    /// <summary>Reads both axes' positions.</summary>
    public async Task<StagePosition> GetPositionAsync(CancellationToken cancellationToken)
    {
        var x = await Stage.X.GetPositionAsync(cancellationToken);
        var y = await Stage.Y.GetPositionAsync(cancellationToken);
        return new StagePosition(x, y);
    }

    /// <summary>Moves one axis by <paramref name="stepUm"/> µm (signed), laser off.</summary>
    /// <exception cref="TestMoveException">The target lies outside the travel.</exception>
    public async Task<StagePosition> JogAsync(StageAxisName axis, double stepUm, CancellationToken cancellationToken)
    {
        if (!double.IsFinite(stepUm))
        {
            throw new TestMoveException($"jog step {stepUm.ToString(CultureInfo.InvariantCulture)} µm is not a number");
        }

        var current = await GetPositionAsync(cancellationToken);
        var step = axis == StageAxisName.X
            ? StageUnits.UmToMicrosteps(stepUm, Profile.X.MicrostepUm)
            : StageUnits.UmToMicrosteps(stepUm, Profile.Y.MicrostepUm);
        var target = axis == StageAxisName.X
            ? current with { XMicrosteps = JobGeometry.Round(current.XMicrosteps + step) }
            : current with { YMicrosteps = JobGeometry.Round(current.YMicrosteps + step) };
        return await MoveAsync(target, cancellationToken);
    }

    /// <summary>Moves to (<paramref name="xMm"/>, <paramref name="yMm"/>) mm, laser off.</summary>
    /// <exception cref="TestMoveException">The target lies outside the travel.</exception>
    public async Task<StagePosition> GoToAsync(double xMm, double yMm, CancellationToken cancellationToken)
    {
        if (!double.IsFinite(xMm) || !double.IsFinite(yMm))
        {
            throw new TestMoveException($"position {N(xMm)},{N(yMm)} mm is not a number");
        }

        var target = new StagePosition(
            JobGeometry.Round(StageUnits.MmToMicrosteps(xMm, Profile.X.MicrostepUm)),
            JobGeometry.Round(StageUnits.MmToMicrosteps(yMm, Profile.Y.MicrostepUm)));
        return await MoveAsync(target, cancellationToken);
    }

    /// <summary>Moves to the job's origin (the top-left corner of the image on the stage), laser off.</summary>
    public async Task<StagePosition> GoToOriginAsync(JobGeometry geometry, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(geometry);
        return await MoveAsync(new StagePosition(geometry.EdgeX(0), geometry.EdgeY(0)), cancellationToken);
    }

    /// <summary>Homes both axes, laser off.</summary>
    public async Task<StagePosition> HomeAsync(CancellationToken cancellationToken)
    {
        await SafelyAsync(
            async () =>
            {
                await Task.WhenAll(Stage.X.HomeAsync(cancellationToken), Stage.Y.HomeAsync(cancellationToken));
            },
            cancellationToken);
        return await GetPositionAsync(cancellationToken);
    }

    /// <summary>Traces the job's bounding rectangle (top-left, top-right, bottom-right, bottom-left, back), laser off,
    /// or at <paramref name="visibleFrequencyHz"/> to see it; ends at the top-left corner with the laser off.</summary>
    /// <exception cref="TestMoveException">The rectangle lies outside the travel, or the frequency is not above 0.</exception>
    public async Task<StagePosition> FrameAsync(JobGeometry geometry, int? visibleFrequencyHz, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(geometry);
        if (visibleFrequencyHz is <= 0)
        {
            throw new TestMoveException($"frame frequency {visibleFrequencyHz} Hz must be above 0 (leave it out to frame with the laser off)");
        }

        return await FrameAsync(geometry.EdgeX(0), geometry.EdgeY(0), geometry.EdgeX(geometry.WidthPx), geometry.EdgeY(geometry.HeightPx), visibleFrequencyHz, cancellationToken);
    }

    /// <summary>Traces a rectangle in microsteps (a drawing's bounding box) from its top-left corner, as <see cref="FrameAsync(JobGeometry, int?, CancellationToken)"/>.</summary>
    public async Task<StagePosition> FrameAsync(long left, long top, long right, long bottom, int? visibleFrequencyHz, CancellationToken cancellationToken)
    {
        if (visibleFrequencyHz is <= 0)
        {
            throw new TestMoveException($"frame frequency {visibleFrequencyHz} Hz must be above 0 (leave it out to frame with the laser off)");
        }

        StagePosition[] corners = [new(left, top), new(right, top), new(right, bottom), new(left, bottom), new(left, top)];
        foreach (var corner in corners)
        {
            CheckTravel(corner);
        }

        await MoveAsync(corners[0], cancellationToken);
        await SafelyAsync(
            async () =>
            {
                if (visibleFrequencyHz is { } hz)
                {
                    await Gate.SetFrequencyAsync(hz, cancellationToken);
                }

                var at = corners[0];
                foreach (var corner in corners.Skip(1))
                {
                    await MoveAxesAsync(at, corner, cancellationToken);
                    at = corner;
                }
            },
            cancellationToken,
            keepAlive: visibleFrequencyHz is not null);
        return corners[^1];
    }

    /// <summary>Fires <paramref name="pulses"/> pulses at <paramref name="frequencyHz"/> at the current position (the gate's burst; on a frequency-only gate, timed by the host), then off.</summary>
    public async Task FirePulsesAsync(int pulses, int frequencyHz, CancellationToken cancellationToken)
    {
        // The job rules' range, as the command line and the app refuse it before a port opens.
        if (JobRules.TestFirePulses(pulses) is { } rule)
        {
            throw new TestMoveException($"test fire of {pulses} pulses: {rule}");
        }

        if (frequencyHz <= 0)
        {
            throw new TestMoveException($"test fire at {frequencyHz} Hz: the frequency must be above 0");
        }

        await SafelyAsync(
            async () =>
            {
                if (Profile.Gate.CountsBursts)
                {
                    await Gate.BurstAsync(pulses, frequencyHz, cancellationToken);

                    // The burst runs on its own; wait it out so the switch-off at the end does not cut it short.
                    await Task.Delay(TimeSpan.FromSeconds((double)pulses / frequencyHz), TimeProvider, cancellationToken);
                }
                else
                {
                    // A frequency-only gate counts nothing: the host switches it off between the last pulse and the one after,
                    // timed from the switch-on's write (each line acts at its last byte, so the shorter off line is sent that much
                    // later), so the count is as good as the two lines' latencies.
                    var gate = Profile.Gate;
                    var byteSeconds = 10.0 / gate.BaudRate;
                    var onLine = string.Format(CultureInfo.InvariantCulture, gate.FrequencyCommand, frequencyHz).Length;
                    var offAfter = TimeSpan.FromSeconds(((pulses - 0.5) / frequencyHz) + ((onLine - gate.OffCommand.Length) * byteSeconds));
                    var written = TimeProvider.GetTimestamp();
                    var on = Gate.SetFrequencyAsync(frequencyHz, cancellationToken);
                    var left = offAfter - TimeProvider.GetElapsedTime(written);
                    if (left > TimeSpan.Zero)
                    {
                        await Task.Delay(left, TimeProvider, cancellationToken);
                    }

                    await on;
                    await Gate.OffAsync(cancellationToken);
                }
            },
            cancellationToken);
    }

    /// <summary>Fires at <paramref name="frequencyHz"/> for <paramref name="duration"/> at the current position, then off.</summary>
    public async Task FireForAsync(TimeSpan duration, int frequencyHz, CancellationToken cancellationToken)
    {
        if (duration <= TimeSpan.Zero || JobRules.TestFireMs((long)Math.Ceiling(duration.TotalMilliseconds)) is not null)
        {
            throw new TestMoveException($"test fire for {duration.TotalMilliseconds.ToString(CultureInfo.InvariantCulture)} ms: {JobRules.TestFireMs(0)}");
        }

        if (frequencyHz <= 0)
        {
            throw new TestMoveException($"test fire at {frequencyHz} Hz: the frequency must be above 0");
        }

        await SafelyAsync(
            async () =>
            {
                await Gate.SetFrequencyAsync(frequencyHz, cancellationToken);
                await Task.Delay(duration, TimeProvider, cancellationToken);
            },
            cancellationToken,
            keepAlive: true);
    }

    private static string N(double value) => value.ToString("0.####", CultureInfo.InvariantCulture);

    private async Task<StagePosition> MoveAsync(StagePosition target, CancellationToken cancellationToken)
    {
        CheckTravel(target);
        await SafelyAsync(
            async () =>
            {
                await Gate.OffAsync(cancellationToken);
                var current = await GetPositionAsync(cancellationToken);
                await MoveAxesAsync(current, target, cancellationToken);
            },
            cancellationToken);
        return target;
    }

    private async Task MoveAxesAsync(StagePosition current, StagePosition to, CancellationToken cancellationToken)
    {
        var moves = new List<Task<long>>();
        if (to.XMicrosteps != current.XMicrosteps)
        {
            moves.Add(Stage.X.MoveAbsoluteAsync(to.XMicrosteps, cancellationToken));
        }

        if (to.YMicrosteps != current.YMicrosteps)
        {
            moves.Add(Stage.Y.MoveAbsoluteAsync(to.YMicrosteps, cancellationToken));
        }

        await Task.WhenAll(moves);
    }

    private void CheckTravel(StagePosition target)
    {
        foreach (var (name, position, axis) in new[] { ("x", target.XMicrosteps, Profile.X), ("y", target.YMicrosteps, Profile.Y) })
        {
            if (position < 0 || position > axis.TravelMicrosteps)
            {
                throw new TestMoveException(
                    $"{name} {N(StageUnits.MicrostepsToMm(position, axis.MicrostepUm))} mm is outside the stage travel 0..{N(axis.TravelMm)} mm");
            }
        }
    }

    /// <summary>Runs a test move at the travel speed and acceleration, and switches the laser off at the end whatever happens.</summary>
    /// <remarks>
    /// The off at the end is the runs' own (<see cref="LaserOff"/>): in doubt within the switch-off's round trip, then every
    /// path at once; a laser that cannot be confirmed off fails the move with that, after whatever else went wrong.
    /// </remarks>
    private async Task SafelyAsync(Func<Task> action, CancellationToken cancellationToken, bool keepAlive = false)
    {
        Exception? keepAliveFault = null;
        Exception? failure = null;
        using var failed = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken);
        var period = keepAlive ? GateKeepAlive.PeriodFor(Profile.Gate.WatchdogMs, RunOptions.Default.KeepAliveFraction) : TimeSpan.Zero;
        var feeder = new GateKeepAlive(Gate, period, TimeProvider, ex =>
        {
            keepAliveFault = ex;
            failed.Cancel();
        })
        {
            Active = keepAlive,
        };
        try
        {
            await using (feeder)
            {
                foreach (var axis in new[] { Stage.X, Stage.Y })
                {
                    await axis.SetAccelerationAsync(StageUnits.AccelerationData(Process.AccelerationMmPerS2, Profile.X.MicrostepUm), cancellationToken);
                    await axis.SetTargetSpeedAsync(StageUnits.SpeedData(Process.TravelSpeedMmPerS, Profile.X.MicrostepUm), cancellationToken);
                }

                await action().WaitAsync(failed.Token);
            }
        }
        catch (OperationCanceledException) when (keepAliveFault is not null)
        {
            failure = new DeviceException($"the laser gate did not answer the keepalive: {keepAliveFault.Message}", keepAliveFault);
        }
        catch (Exception ex)
        {
            failure = ex;
        }

        // Not cancellable: the laser goes off even when the operation was cancelled.
        var off = await new LaserOff(Gate, TimeProvider) { GateNeverReplies = Profile.Gate.NeverReplies }.SwitchOffAsync(LaserOff.ConfirmWindow(Process, Profile), Profile.Gate.WatchdogMs);
        // A gate that never replies can only be sent off: its OFF written is all a test move can do, and the move goes on
        // (its front ends say "sent off", never "off"); a run's log keeps that it was not confirmed.
        if (!off.Confirmed && !(Profile.Gate.NeverReplies && off.Path != LaserOffPath.None))
        {
            throw failure is null ? new DeviceException(off.Problem!) : new DeviceException($"{failure.Message}; {off.Problem}", failure);
        }

        if (failure is not null)
        {
            System.Runtime.ExceptionServices.ExceptionDispatchInfo.Throw(failure);
        }
    }
}

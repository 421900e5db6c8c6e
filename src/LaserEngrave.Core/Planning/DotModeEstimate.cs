using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Motion;

namespace LaserEngrave.Core.Planning;

/// <summary>What dot mode (<see cref="PlanMode.Dots"/>) costs per dot: step, commands, settle and the burst. Planning data only; no executor runs it yet.</summary>
/// <remarks>
/// Every burnt pixel is a dot. At each dot the stage steps one pitch from the previous dot (a trapezoid at the burn
/// speed and acceleration, quantised as the Zaber devices quantise them), the Move Absolute and its reply cross the
/// stage line, the stage settles for <see cref="ProcessSettings.DotSettleMs"/>, the gate is sent `BURST n f` and answers
/// `OK BURST n`, and the laser fires for N / f (seed 004: any dwell in [N T, N T + tg) gives exactly N pulses).
/// Travel between rows and between runs is as in raster mode and not counted here.
/// </remarks>
public sealed record DotModeEstimate
{
    private const double BitsPerByte = 10;
    private const int ZaberFrameBytes = 6;

    public required long Dots { get; init; }

    public required int PulsesPerDot { get; init; }

    /// <summary>Time the laser fires at one dot: N / f, seconds.</summary>
    public required double BurstSeconds { get; init; }

    public required double SettleSeconds { get; init; }

    /// <summary>The one-pitch step from the previous dot, seconds.</summary>
    public required double StepSeconds { get; init; }

    /// <summary>Move Absolute and its reply, and `BURST n f` and its reply, seconds.</summary>
    public required double CommandSeconds { get; init; }

    /// <summary>Dwell at a dot: burst plus settle, seconds.</summary>
    public double DwellSeconds => BurstSeconds + SettleSeconds;

    public double SecondsPerDot => StepSeconds + CommandSeconds + DwellSeconds;

    /// <summary>All dots, seconds (travel between runs not included).</summary>
    public double DotsSeconds => Dots * SecondsPerDot;

    public static DotModeEstimate For(BitMask mask, JobGeometry geometry, ProcessSettings process, LaserGateProfile? gate = null)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentNullException.ThrowIfNull(geometry);
        ArgumentNullException.ThrowIfNull(process);
        process.Validate();
        gate ??= new LaserGateProfile();
        var n = process.PulsesPerDot;
        var f = process.LaserFrequencyWholeHz;
        var burstLine = string.Format(CultureInfo.InvariantCulture, gate.BurstCommand, n, f) + gate.LineTerminator;
        var burstReply = $"{gate.AckPrefix} BURST {n}{gate.LineTerminator}";
        var speed = StageUnits.SpeedMicrostepsPerS(StageUnits.SpeedData(process.BurnSpeedMmPerS, geometry.MicrostepUm));
        var acceleration = StageUnits.AccelerationMicrostepsPerS2(StageUnits.AccelerationData(process.AccelerationMmPerS2, geometry.MicrostepUm));
        return new DotModeEstimate
        {
            Dots = mask.CountSet(),
            PulsesPerDot = n,
            BurstSeconds = (double)n / f,
            SettleSeconds = process.DotSettleMs / 1000,
            StepSeconds = new TrapezoidProfile(geometry.PitchMicrosteps, speed, acceleration).Duration,
            CommandSeconds = (2 * ZaberFrameBytes * BitsPerByte / process.StageBaudRate)
                + ((burstLine.Length + burstReply.Length) * BitsPerByte / process.GateBaudRate),
        };
    }
}

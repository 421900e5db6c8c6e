using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Planning;

/// <summary>One stop of dot mode: where the stage stands while the gate fires its burst, whole microsteps.</summary>
/// <param name="X">Stage X, microsteps.</param>
/// <param name="Y">Stage Y, microsteps.</param>
/// <param name="Row">Image row the dot burns on.</param>
public readonly record struct Dot(long X, long Y, int Row);

/// <summary>A dot-mode plan (<see cref="PlanMode.Dots"/>): the stops along every run of black pixels, generated row by row on demand.</summary>
/// <remarks>
/// <para>
/// With <see cref="ProcessSettings.DotPitchMicrosteps"/> 0 every black pixel gets one dot at its centre:
/// x = round(ox + (c + 0.5) p), on the row's centre line y = round(oy + (r + 0.5) p). With a dot pitch k a run of
/// black pixels [c0, c1), L = (c1 - c0) p long, gets n = max(1, floor(L / k)) dots k apart, centred on the run: the
/// first (L - (n - 1) k) / 2 from its left edge. Every position is computed from absolute values and rounded once
/// (<see cref="JobGeometry.PointX"/>); on a calibrated machine the rows are sheared as the raster's are.
/// </para>
/// <para>
/// Rows are visited top to bottom, serpentine when <see cref="PlanOptions.Bidirectional"/> (each visited row the other
/// way), dots along a row in its direction. The plan reads the mask each time it is enumerated.
/// </para>
/// </remarks>
public sealed class DotPlan
{
    private readonly ProcessSettings _process;
    private readonly LaserGateProfile _gate;

    public DotPlan(BitMask mask, JobGeometry geometry, ProcessSettings process, MachineProfile profile, PlanOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(mask);
        ArgumentNullException.ThrowIfNull(geometry);
        ArgumentNullException.ThrowIfNull(process);
        ArgumentNullException.ThrowIfNull(profile);
        if (mask.Width != geometry.WidthPx || mask.Height != geometry.HeightPx)
        {
            throw new PlanException($"the mask is {mask.Width} x {mask.Height} pixels but the geometry is for {geometry.WidthPx} x {geometry.HeightPx}");
        }

        Mask = mask;
        Geometry = geometry;
        Options = options ?? PlanOptions.Default;
        PulsesPerDot = process.PulsesPerDot;
        DotPitchMicrosteps = process.DotPitchMicrosteps;
        Timing = new DotTiming(process, profile, geometry.MicrostepUm);

        _process = process;
        _gate = profile.Gate;
        Estimate = DotModeEstimate.For(Program());
        Warnings = Timing.BurstProblem is { } problem
            ? [new JobWarning(JobWarningKind.BurstTooLongForTheWatchdog, problem + " (engraving is refused)")]
            : [];
    }

    public BitMask Mask { get; }

    public JobGeometry Geometry { get; }

    public PlanOptions Options { get; }

    public int PulsesPerDot { get; }

    /// <summary>Distance between dots along a run, microsteps; 0: one dot at every pixel's centre.</summary>
    public long DotPitchMicrosteps { get; }

    /// <summary>The timing model the executor follows and the estimate adds up.</summary>
    public DotTiming Timing { get; }

    /// <summary>Dots, rows and the estimated duration, added up in one pass over the dots.</summary>
    public DotModeEstimate Estimate { get; }

    /// <summary>Null when the plan can be engraved; otherwise why not, in one line.</summary>
    public string? Problem => Timing.BurstProblem;

    public IReadOnlyList<JobWarning> Warnings { get; }

    /// <summary>The distance between dots along a run, µm (the pixel pitch when a dot sits on every pixel).</summary>
    public double DotSpacingUm => DotPitchMicrosteps > 0 ? DotPitchMicrosteps * Geometry.MicrostepUm : Geometry.PitchUm;

    /// <summary>The device-unit program of this plan: every dot's target and burst, in order (what is sent, estimated and resumed).</summary>
    public DotProgram Program() => new(this, _process, _gate);

    /// <summary>Every dot in order.</summary>
    public IEnumerable<Dot> Dots() => Dots(0);

    /// <summary>The dots from index <paramref name="first"/> on (for resuming a run), in the order of <see cref="Dots()"/>.</summary>
    public IEnumerable<Dot> Dots(long first)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(first);
        return Enumerate(first);
    }

    private IEnumerable<Dot> Enumerate(long first)
    {
        var runs = new int[64];
        var row = new List<Dot>();
        long index = 0;
        var visited = 0;
        for (var r = 0; r < Mask.Height; r++)
        {
            var count = RowRuns.Find(Mask.ReadRow(r), ref runs);
            if (count == 0)
            {
                continue;
            }

            row.Clear();
            var y = Geometry.RowY(r);
            for (var i = 0; i < count; i++)
            {
                AddRun(row, runs[2 * i], runs[(2 * i) + 1], r, y);
            }

            var leftToRight = !Options.Bidirectional || visited % 2 == 0;
            visited++;
            if (index + row.Count <= first)
            {
                index += row.Count;
                continue;
            }

            for (var i = 0; i < row.Count; i++)
            {
                if (index++ >= first)
                {
                    yield return row[leftToRight ? i : row.Count - 1 - i];
                }
            }
        }
    }

    private void AddRun(List<Dot> row, int c0, int c1, int r, long y)
    {
        if (DotPitchMicrosteps == 0)
        {
            for (var c = c0; c < c1; c++)
            {
                row.Add(new Dot(Geometry.PointX(c + 0.5, r), y, r));
            }

            return;
        }

        // In pixel widths along the row: the run is c1 - c0 wide, the dots k / pX apart.
        var step = DotPitchMicrosteps / Geometry.PitchXMicrosteps;
        var length = c1 - c0;
        var n = Math.Max(1, (long)Math.Floor((length / step) + 1e-9));
        var firstAt = c0 + ((length - ((n - 1) * step)) / 2);
        for (long i = 0; i < n; i++)
        {
            row.Add(new Dot(Geometry.PointX(firstAt + (i * step), r), y, r));
        }
    }

    /// <summary>The dot pitch as the log and the command line say it.</summary>
    public string DescribePitch() =>
        DotPitchMicrosteps == 0
            ? "every pixel"
            : string.Create(CultureInfo.InvariantCulture, $"{DotPitchMicrosteps} microsteps ({DotSpacingUm:0.###} µm)");
}

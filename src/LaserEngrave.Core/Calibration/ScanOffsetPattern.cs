using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Calibration;

/// <summary>
/// The bidirectional scan offset test pattern: a row of short vertical bars. Engraved bidirectionally, every row of the
/// mask is visited and rows alternate direction, so each bar is drawn half left to right (its 1st, 3rd, ... rows from
/// the top) and half right to left (its 2nd, 4th, ...): any offset between the two directions shows as edges that zigzag
/// from row to row. LightBurn's "scanning offset adjustment" test, engraved once per speed.
/// </summary>
public sealed class ScanOffsetPattern
{
    /// <summary>Most bars a pattern may have.</summary>
    public const int MaxBars = 100;

    /// <summary>Widest and tallest pattern, pixels: far beyond a useful test, and a mask that size is still small.</summary>
    public const int MaxSidePx = 20_000;

    private ScanOffsetPattern(double pitchUm, int bars, int barWidthPx, int barHeightPx, int gapPx)
    {
        PitchUm = pitchUm;
        Bars = bars;
        BarWidthPx = barWidthPx;
        BarHeightPx = barHeightPx;
        GapPx = gapPx;
    }

    public double PitchUm { get; }

    public int Bars { get; }

    public int BarWidthPx { get; }

    /// <summary>Rows of every bar: even, so that half are burned in each direction.</summary>
    public int BarHeightPx { get; }

    /// <summary>Space between two bars, pixels.</summary>
    public int GapPx { get; }

    public int WidthPx => (Bars * BarWidthPx) + ((Bars - 1) * GapPx);

    public int HeightPx => BarHeightPx;

    public double WidthMm => Units.StepsToMm(WidthPx, PitchUm);

    public double HeightMm => Units.StepsToMm(HeightPx, PitchUm);

    /// <summary>Lays out <paramref name="bars"/> bars on a grid of <paramref name="pitchUm"/>; sizes are rounded to whole pixels, the height to an even number of rows.</summary>
    public static ScanOffsetPattern Create(double pitchUm, double barWidthUm, double barHeightUm, int bars, double gapUm)
    {
        Positive(pitchUm, "pitch", "µm");
        Positive(barWidthUm, "bar width", "µm");
        Positive(barHeightUm, "bar height", "µm");
        Positive(gapUm, "gap", "µm");
        if (bars is < 1 or > MaxBars)
        {
            throw new CalibrationException($"{bars} bars: give 1..{MaxBars}");
        }

        var width = Px(barWidthUm, pitchUm, "bar width");
        var height = Px(barHeightUm, pitchUm, "bar height");
        height = Math.Max(2, height + (height % 2));
        var gap = Px(gapUm, pitchUm, "gap");
        var total = ((long)bars * width) + ((long)(bars - 1) * gap);
        if (total > MaxSidePx || height > MaxSidePx)
        {
            throw new CalibrationException($"a pattern of {bars} bars is {total} x {height} pixels at {N(pitchUm)} µm; it needs at most {MaxSidePx} a side: fewer or smaller bars, or a larger pitch");
        }

        return new ScanOffsetPattern(pitchUm, bars, width, height, gap);
    }

    /// <summary>The pattern as a burn mask (set = burn).</summary>
    public BitMask ToMask()
    {
        var mask = new BitMask(WidthPx, HeightPx);
        for (var bar = 0; bar < Bars; bar++)
        {
            var left = bar * (BarWidthPx + GapPx);
            for (var row = 0; row < HeightPx; row++)
            {
                for (var column = left; column < left + BarWidthPx; column++)
                {
                    mask[column, row] = true;
                }
            }
        }

        return mask;
    }

    /// <summary>What the pattern is, in lines for the technician.</summary>
    public IEnumerable<string> Describe()
    {
        var c = CultureInfo.InvariantCulture;
        yield return string.Create(c, $"Pattern: {Bars} bars {BarWidthPx * PitchUm:0.###} µm wide and {BarHeightPx * PitchUm:0.###} µm tall ({BarHeightPx} rows), {GapPx * PitchUm:0.###} µm apart; {WidthPx} x {HeightPx} px at {PitchUm:0.###} µm, {WidthMm:0.###} x {HeightMm:0.###} mm");
        yield return "Engraved bidirectionally, each bar's 1st, 3rd, ... rows from the top are burned left to right and its 2nd, 4th, ... right to left";
    }

    private static int Px(double um, double pitchUm, string what)
    {
        var px = Math.Round(um / pitchUm);
        return px < 1
            ? throw new CalibrationException($"{what} {N(um)} µm is less than one pixel of {N(pitchUm)} µm")
            : px > MaxSidePx ? throw new CalibrationException($"{what} {N(um)} µm is more than {MaxSidePx} pixels of {N(pitchUm)} µm") : (int)px;
    }

    private static void Positive(double value, string what, string unit)
    {
        if (!(value > 0) || double.IsInfinity(value))
        {
            throw new CalibrationException($"{what} {N(value)} {unit} must be a finite number above 0");
        }
    }

    private static string N(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);
}

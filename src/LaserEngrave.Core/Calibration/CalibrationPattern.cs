using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Core.Calibration;

/// <summary>
/// The calibration pattern (seed 002): two long grooves along X and Y crossing near the top-left corner, scale marks
/// across each groove at known distances from the crossing, and a square whose corner A (nearest the crossing) carries
/// a filled marker. Every distance is a whole number of pixels, so the nominal values below are exact on the job's grid.
/// </summary>
/// <remarks>
/// Lines are <see cref="LineWidthPx"/> pixels wide; a line's position is its centre line. The square's corners are
/// A (top-left), B (top-right, +X from A), C (bottom-right) and D (bottom-left, +Y from A); the diagonals are AC and BD.
/// </remarks>
public sealed class CalibrationPattern
{
    /// <summary>Smallest pattern, pixels per side: below this the marks run into each other.</summary>
    public const int MinSidePx = 100;

    private CalibrationPattern(double sizeMm, double pitchUm, int sidePx, int lineWidthPx, int marginPx, int markSpacingPx, int markCount, int squareOffsetPx, int squareSidePx)
    {
        SizeMm = sizeMm;
        PitchUm = pitchUm;
        SidePx = sidePx;
        LineWidthPx = lineWidthPx;
        MarginPx = marginPx;
        MarkSpacingPx = markSpacingPx;
        MarkCount = markCount;
        SquareOffsetPx = squareOffsetPx;
        SquareSidePx = squareSidePx;
    }

    public double SizeMm { get; }

    public double PitchUm { get; }

    /// <summary>Pixels per side of the (square) mask.</summary>
    public int SidePx { get; }

    public int LineWidthPx { get; }

    /// <summary>Left and top edge of both grooves, pixels.</summary>
    public int MarginPx { get; }

    public int MarkSpacingPx { get; }

    /// <summary>Scale marks on each groove (mark k is k x spacing from the crossing, k = 1..count).</summary>
    public int MarkCount { get; }

    /// <summary>Distance from the grooves to the square's top and left sides, pixels (line edge to line edge).</summary>
    public int SquareOffsetPx { get; }

    /// <summary>The square's side, centre line to centre line, pixels.</summary>
    public int SquareSidePx { get; }

    /// <summary>Distance between scale marks, mm.</summary>
    public double MarkSpacingMm => Mm(MarkSpacingPx);

    /// <summary>The square's side, centre line to centre line, mm.</summary>
    public double SquareSideMm => Mm(SquareSidePx);

    /// <summary>Where the grooves' centre lines cross.</summary>
    public PatternPoint Crossing => new(Mm(MarginPx + (LineWidthPx / 2.0)), Mm(MarginPx + (LineWidthPx / 2.0)));

    /// <summary>Nominal distance of scale mark <paramref name="k"/> (1..<see cref="MarkCount"/>) from the crossing, mm.</summary>
    public double MarkDistanceMm(int k) => Mm(k * MarkSpacingPx);

    /// <summary>Centre of scale mark <paramref name="k"/> on the X groove (k = 0 is the crossing).</summary>
    public PatternPoint XMark(int k) => new(Crossing.XMm + MarkDistanceMm(k), Crossing.YMm);

    /// <summary>Centre of scale mark <paramref name="k"/> on the Y groove (k = 0 is the crossing).</summary>
    public PatternPoint YMark(int k) => new(Crossing.XMm, Crossing.YMm + MarkDistanceMm(k));

    public PatternPoint SquareA => new(Mm(SquareLinePx + (LineWidthPx / 2.0)), Mm(SquareLinePx + (LineWidthPx / 2.0)));

    public PatternPoint SquareB => new(SquareA.XMm + SquareSideMm, SquareA.YMm);

    public PatternPoint SquareC => new(SquareA.XMm + SquareSideMm, SquareA.YMm + SquareSideMm);

    public PatternPoint SquareD => new(SquareA.XMm, SquareA.YMm + SquareSideMm);

    private int SquareLinePx => MarginPx + LineWidthPx + SquareOffsetPx;

    /// <summary>Lays out a pattern of <paramref name="sizeMm"/> square at <paramref name="pitchUm"/> per pixel.</summary>
    /// <param name="lineWidthUm">Width of every line (default 20 µm, about one spot).</param>
    /// <param name="markSpacingMm">Distance between scale marks (default a tenth of the size).</param>
    public static CalibrationPattern Create(double sizeMm, double pitchUm, double lineWidthUm = 20, double? markSpacingMm = null)
    {
        Positive(sizeMm, "pattern size", "mm");
        Positive(pitchUm, "pitch", "µm");
        Positive(lineWidthUm, "line width", "µm");
        if (markSpacingMm is { } spacing)
        {
            Positive(spacing, "mark spacing", "mm");
        }

        var n = Units.MmToSteps(sizeMm, pitchUm);
        if (n < MinSidePx || n > BitMask.MaxSide)
        {
            throw new CalibrationException(
                $"a {N(sizeMm)} mm pattern at {N(pitchUm)} µm is {N(Math.Round(n))} pixels per side; it needs {MinSidePx}..{BitMask.MaxSide}: change the size or the pitch");
        }

        var side = (int)Math.Round(n);
        var width = Math.Max(1, (int)Math.Round(lineWidthUm / pitchUm));
        var margin = Math.Max(width * 4, (int)Math.Round(0.05 * side));
        var markSpacing = (int)Math.Round(Units.MmToSteps(markSpacingMm ?? (sizeMm / 10), pitchUm));
        if (markSpacing < 4 * width)
        {
            throw new CalibrationException($"scale marks {N(Units.StepsToMm(markSpacing, pitchUm))} mm apart are too close for {N(width * pitchUm)} µm lines");
        }

        var marks = (side - margin - margin - width) / markSpacing;
        if (marks < 1)
        {
            throw new CalibrationException($"scale marks {N(Units.StepsToMm(markSpacing, pitchUm))} mm apart do not fit a {N(sizeMm)} mm pattern");
        }

        var offset = (int)Math.Round(0.15 * side);
        var square = (int)Math.Round(0.6 * side);
        if (width * 6 > square || margin + width + offset + square + width > side)
        {
            throw new CalibrationException($"{N(lineWidthUm)} µm lines are too wide for a {N(sizeMm)} mm pattern");
        }

        return new CalibrationPattern(sizeMm, pitchUm, side, width, margin, markSpacing, marks, offset, square);
    }

    /// <summary>The pattern as a burn mask (set = burn), <see cref="SidePx"/> square.</summary>
    public BitMask ToMask()
    {
        var mask = new BitMask(SidePx, SidePx);
        var w = LineWidthPx;
        var m = MarginPx;
        var end = SidePx - m;
        var tick = Math.Max(3 * w, (int)Math.Round(0.02 * SidePx));

        // The grooves: X along the top, Y down the left, crossing at (m, m).
        Fill(mask, m, m, end - m, w);
        Fill(mask, m, m, w, end - m);
        for (var k = 1; k <= MarkCount; k++)
        {
            var at = m + (k * MarkSpacingPx);
            Fill(mask, at, m - tick, w, w + (2 * tick));
            Fill(mask, m - tick, at, w + (2 * tick), w);
        }

        // The square's outline, then the marker inside corner A.
        var s = SquareLinePx;
        var q = SquareSidePx;
        Fill(mask, s, s, q + w, w);
        Fill(mask, s, s + q, q + w, w);
        Fill(mask, s, s, w, q + w);
        Fill(mask, s + q, s, w, q + w);
        var marker = Math.Max(3 * w, (int)Math.Round(0.03 * SidePx));
        var inset = Math.Max(2 * w, (int)Math.Round(0.02 * SidePx));
        Fill(mask, s + w + inset, s + w + inset, marker, marker);
        return mask;
    }

    /// <summary>Lines for the technician: what to measure and every nominal distance.</summary>
    public IEnumerable<string> Describe()
    {
        var c = CultureInfo.InvariantCulture;
        yield return string.Create(c, $"Pattern: {SizeMm:0.###} mm square, {SidePx} x {SidePx} px at {PitchUm:0.###} µm, lines {LineWidthPx * PitchUm:0.###} µm wide");
        yield return string.Create(c, $"Grooves cross at ({Crossing.XMm:0.####}, {Crossing.YMm:0.####}) mm from the job's top-left corner");
        yield return string.Create(c, $"Scale marks every {MarkSpacingMm:0.####} mm on both grooves, at {string.Join(", ", Enumerable.Range(1, MarkCount).Select(k => MarkDistanceMm(k).ToString("0.####", c)))} mm from the crossing");
        yield return string.Create(c, $"Square: side {SquareSideMm:0.####} mm, diagonals {SquareSideMm * Math.Sqrt(2):0.####} mm; corner A carries the filled marker, B is along X, D along Y, C opposite A");
    }

    private double Mm(double px) => Units.StepsToMm(px, PitchUm);

    private static void Fill(BitMask mask, int x, int y, int width, int height)
    {
        for (var row = Math.Max(0, y); row < Math.Min(mask.Height, y + height); row++)
        {
            for (var column = Math.Max(0, x); column < Math.Min(mask.Width, x + width); column++)
            {
                mask[column, row] = true;
            }
        }
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

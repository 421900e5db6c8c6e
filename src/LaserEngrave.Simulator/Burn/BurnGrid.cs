using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Simulator.Burn;

/// <summary>A job's pixel grid on the stage, in microsteps, as the burn recorder reads it.</summary>
/// <remarks>
/// Pixel <c>c</c> of a row spans x in [<see cref="ColumnEdge"/>(c), <see cref="ColumnEdge"/>(c + 1)); row <c>r</c> is burned
/// along y = <see cref="RowLine"/>(r), and its cell spans y in [<see cref="RowEdge"/>(r), <see cref="RowEdge"/>(r + 1)) (where a
/// pulse lands on the row). Every edge is computed from the unrounded origin and pitch and rounded once, half
/// away from zero, the same rule as the planner's job geometry.
/// </remarks>
public sealed record BurnGrid
{
    public BurnGrid(double originXMicrosteps, double originYMicrosteps, double pitchMicrosteps, int widthPx, int heightPx)
    {
        if (!(pitchMicrosteps >= 1) || double.IsInfinity(pitchMicrosteps))
        {
            throw new ArgumentOutOfRangeException(nameof(pitchMicrosteps), pitchMicrosteps, "the pitch must be at least one microstep");
        }

        if (widthPx <= 0 || heightPx <= 0)
        {
            throw new ArgumentOutOfRangeException(nameof(widthPx), $"a grid of {widthPx} x {heightPx} pixels is empty");
        }

        OriginXMicrosteps = originXMicrosteps;
        OriginYMicrosteps = originYMicrosteps;
        PitchMicrosteps = pitchMicrosteps;
        WidthPx = widthPx;
        HeightPx = heightPx;
    }

    /// <summary>The grid a job's geometry puts on the stage.</summary>
    public static BurnGrid For(JobGeometry geometry)
    {
        ArgumentNullException.ThrowIfNull(geometry);
        return new BurnGrid(geometry.OriginXMicrosteps, geometry.OriginYMicrosteps, geometry.PitchMicrosteps, geometry.WidthPx, geometry.HeightPx);
    }

    /// <summary>x of the left edge of column 0, unrounded.</summary>
    public double OriginXMicrosteps { get; }

    /// <summary>y of the top edge of row 0, unrounded.</summary>
    public double OriginYMicrosteps { get; }

    /// <summary>Pixel pitch, unrounded.</summary>
    public double PitchMicrosteps { get; }

    public int WidthPx { get; }

    public int HeightPx { get; }

    /// <summary>Rounds a position to the whole microstep the stage is sent: half away from zero.</summary>
    public static long Round(double microsteps) => (long)Math.Round(microsteps, MidpointRounding.AwayFromZero);

    /// <summary>x of the left edge of column <paramref name="column"/> (the right edge of the previous one).</summary>
    public long ColumnEdge(int column) => Round(Math.FusedMultiplyAdd(column, PitchMicrosteps, OriginXMicrosteps));

    /// <summary>y of the centre line along which row <paramref name="row"/> is burned.</summary>
    public long RowLine(int row) => Round(Math.FusedMultiplyAdd(row + 0.5, PitchMicrosteps, OriginYMicrosteps));

    /// <summary>y of the top edge of row <paramref name="row"/>'s cell (the bottom edge of the previous one).</summary>
    public long RowEdge(int row) => Round(Math.FusedMultiplyAdd(row, PitchMicrosteps, OriginYMicrosteps));

    /// <summary>The row whose cell holds <paramref name="y"/>: -1 above the grid, <see cref="HeightPx"/> below it.</summary>
    public int RowCellAt(double y) => CellAt(y, OriginYMicrosteps, HeightPx, columns: false);

    /// <summary>The row whose centre line is <paramref name="y"/>, or -1.</summary>
    public int RowAt(long y)
    {
        var guess = (int)Math.Clamp(Math.Floor(((y - OriginYMicrosteps) / PitchMicrosteps) - 0.5), -2, HeightPx + 1);
        for (var row = Math.Max(0, guess - 1); row <= Math.Min(HeightPx - 1, guess + 2); row++)
        {
            if (RowLine(row) == y)
            {
                return row;
            }
        }

        return -1;
    }

    /// <summary>The column whose span holds <paramref name="x"/>: -1 left of the grid, <see cref="WidthPx"/> right of it.</summary>
    public int ColumnAt(double x) => CellAt(x, OriginXMicrosteps, WidthPx, columns: true);

    // The column (or row) whose [edge(i), edge(i + 1)) holds `at`: -1 before the first, `count` after the last.
    private int CellAt(double at, double origin, int count, bool columns)
    {
        if (at < Edge(0))
        {
            return -1;
        }

        if (at >= Edge(count))
        {
            return count;
        }

        var cell = (int)Math.Clamp(Math.Floor((at - origin) / PitchMicrosteps), 0, count - 1);
        while (cell > 0 && at < Edge(cell))
        {
            cell--;
        }

        while (cell < count - 1 && at >= Edge(cell + 1))
        {
            cell++;
        }

        return cell;

        long Edge(int i) => columns ? ColumnEdge(i) : RowEdge(i);
    }
}

using System.Runtime.CompilerServices;
using LaserEngrave.Core;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Simulator.Burn;

/// <summary>Collects the outermost pulses of every burn run of the expected image, and from them the <see cref="EdgeFigures"/>.</summary>
/// <remarks>
/// A burn run is a maximal horizontal run of black pixels, columns c0..c1 of a row. Its pulses are those whose centre
/// lies in the row's cell (y) and within the run's catchment along x: the run widened on each side by half the white gap
/// to the neighbouring run of the same row, or, on a side without one, by all the white up to the grid's border and one
/// pixel beyond it. The catchments of a row meet halfway across every gap, so a pulse belongs to at most one run.
/// </remarks>
internal sealed class EdgeMeter
{
    private readonly BurnGrid _grid;
    private readonly int[] _firstRunOfRow;
    private readonly Run[] _runs;
    private int _lastRun = -1;

    public EdgeMeter(BurnGrid grid, BitMask expected)
    {
        _grid = grid;
        _firstRunOfRow = new int[grid.HeightPx + 1];
        var runs = new List<Run>();
        for (var row = 0; row < grid.HeightPx; row++)
        {
            _firstRunOfRow[row] = runs.Count;
            var previousEnd = -1;
            for (var column = 0; column < grid.WidthPx; column++)
            {
                if (!expected[column, row] || (column > 0 && expected[column - 1, row]))
                {
                    continue;
                }

                var end = column;
                while (end + 1 < grid.WidthPx && expected[end + 1, row])
                {
                    end++;
                }

                var lo = previousEnd < 0
                    ? grid.ColumnEdge(0) - grid.PitchMicrosteps
                    : (grid.ColumnEdge(previousEnd + 1) + grid.ColumnEdge(column)) / 2.0;
                if (runs.Count > _firstRunOfRow[row])
                {
                    runs[^1] = runs[^1] with { CatchHi = lo };
                }

                runs.Add(new Run(row, column, end, lo, grid.ColumnEdge(grid.WidthPx) + grid.PitchMicrosteps));
                previousEnd = end;
            }
        }

        _firstRunOfRow[grid.HeightPx] = runs.Count;
        _runs = [.. runs];
    }

    /// <summary>A pulse landed at <paramref name="x"/> in row <paramref name="row"/>'s cell (-1 or the height when off the grid).</summary>
    [MethodImpl(HotPath.Optimized)]
    public void Add(int row, double x, double frequencyHz)
    {
        if (row < 0 || row >= _grid.HeightPx)
        {
            return;
        }

        // Pulses come in time order, so most land in the same run as the one before.
        var index = _lastRun >= 0 && _runs[_lastRun].Row == row && Catches(_runs[_lastRun], x) ? _lastRun : Find(row, x);
        if (index < 0)
        {
            return;
        }

        _lastRun = index;
        ref var run = ref _runs[index];
        if (!(x >= run.MinX))
        {
            run = run with { MinX = x, MinHz = frequencyHz };
        }

        if (!(x <= run.MaxX))
        {
            run = run with { MaxX = x, MaxHz = frequencyHz };
        }
    }

    /// <param name="burnSpeedUmPerS">The burn speed, from which a run's pulse spacing follows.</param>
    /// <param name="xMicrostepUm">Length of an X microstep.</param>
    public EdgeFigures Figures(double burnSpeedUmPerS, double xMicrostepUm)
    {
        int ends = 0, missing = 0;
        double sum = 0, max = 0;
        foreach (var run in _runs)
        {
            if (double.IsNaN(run.MinX))
            {
                missing++;
                continue;
            }

            var left = Math.Abs(((run.MinX - _grid.ColumnEdge(run.FirstColumn)) * xMicrostepUm) - (burnSpeedUmPerS / run.MinHz / 2));
            var right = Math.Abs(((_grid.ColumnEdge(run.LastColumn + 1) - run.MaxX) * xMicrostepUm) - (burnSpeedUmPerS / run.MaxHz / 2));
            ends += 2;
            sum += left + right;
            max = Math.Max(max, Math.Max(left, right));
        }

        return new EdgeFigures(ends, ends == 0 ? 0 : sum / ends, max, missing);
    }

    private static bool Catches(in Run run, double x) => x >= run.CatchLo && x < run.CatchHi;

    // The run of `row` whose catchment holds x, or -1.
    private int Find(int row, double x)
    {
        int lo = _firstRunOfRow[row], hi = _firstRunOfRow[row + 1] - 1;
        if (hi < lo || x < _runs[lo].CatchLo)
        {
            return -1;
        }

        while (lo < hi)
        {
            var mid = (lo + hi + 1) / 2;
            if (_runs[mid].CatchLo <= x)
            {
                lo = mid;
            }
            else
            {
                hi = mid - 1;
            }
        }

        return Catches(_runs[lo], x) ? lo : -1;
    }

    /// <summary>A burn run, its catchment [CatchLo, CatchHi) in microsteps, and its outermost pulses so far (NaN before the first).</summary>
    private readonly record struct Run(int Row, int FirstColumn, int LastColumn, double CatchLo, double CatchHi)
    {
        public double MinX { get; init; } = double.NaN;

        public double MaxX { get; init; } = double.NaN;

        public double MinHz { get; init; }

        public double MaxHz { get; init; }
    }
}

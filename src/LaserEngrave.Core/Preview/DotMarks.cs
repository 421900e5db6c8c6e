using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Preview;

/// <summary>
/// How many of a dot part's drawn moves are burned once its dots have fired: the picture draws the part's raster plan (its
/// burn runs and travels) while the run counts dots, so each dot marks the burn run that holds it and every move drawn
/// before. Kept as steps: from dot <see cref="FromDot"/>[i] on (0-based, in <see cref="DotProgram.Steps"/> order),
/// <see cref="Burned"/>[i] moves; at most one step per drawn burn run, however many dots there are.
/// </summary>
/// <remarks>
/// A dot belongs to the run of black pixels it was placed in (found from the mask, as <see cref="DotPlan"/> places it),
/// and that run to the drawn burn move that scans it: the raster plan burns each run of a row in one move, in the row's
/// direction. The marks never go back: where the plan scans a row the other way than the dots visit it (a paper plan
/// scans every row left to right), every dot fired is marked burned and a few not yet fired in its row with it.
/// </remarks>
/// <param name="FromDot">The first dot of each step, ascending.</param>
/// <param name="Burned">The drawn moves burned from that dot on, ascending.</param>
public sealed record DotMarks(long[] FromDot, int[] Burned)
{
    /// <summary>The drawn moves burned once <paramref name="dotsDone"/> dots have fired.</summary>
    public int After(long dotsDone)
    {
        if (dotsDone <= 0)
        {
            return 0;
        }

        var i = Array.BinarySearch(FromDot, dotsDone - 1);
        i = i >= 0 ? i : ~i - 1;
        return i < 0 ? 0 : Burned[i];
    }

    /// <summary>The marks of a dot plan's dots on its picture: the plan's burn moves drawn (in picture order), out of <paramref name="drawn"/> moves.</summary>
    /// <param name="plan">The dot plan whose program is run.</param>
    /// <param name="burns">Each drawn burn move: its image row, its index among the part's drawn moves, whether it goes left to right.</param>
    /// <param name="drawn">The part's moves drawn; a dot in a run not drawn (past the cap) marks them all.</param>
    internal static DotMarks Of(DotPlan plan, IReadOnlyList<(int Row, int At, bool LeftToRight)> burns, int drawn)
    {
        var runs = new int[64];

        // Which drawn move burns each run (row, run from the left): a row's runs are burned one move each, in its direction.
        var burnAt = new Dictionary<(int Row, int Run), int>(burns.Count);
        int row = -1, count = 0, seen = 0;
        foreach (var (r, at, leftToRight) in burns)
        {
            if (r != row)
            {
                (row, seen) = (r, 0);
                count = RowRuns.Find(plan.Mask.ReadRow(row), ref runs);
            }

            burnAt[(row, leftToRight ? seen : count - 1 - seen)] = at;
            seen++;
        }

        var from = new List<long>();
        var burned = new List<int>();
        var done = 0;
        var bounds = Array.Empty<long>();
        row = -1;
        foreach (var dot in plan.Program().Steps())
        {
            if (dot.Row != row)
            {
                row = dot.Row;
                bounds = Bounds(plan, row, ref runs);
            }

            // The run of the dot: the one before the first boundary right of it (boundaries halfway across the white between runs).
            var run = Array.BinarySearch(bounds, dot.X);
            run = run >= 0 ? run + 1 : ~run;
            var marks = burnAt.TryGetValue((row, run), out var at) ? at + 1 : drawn;
            if (marks > done)
            {
                done = marks;
                from.Add(dot.Index);
                burned.Add(done);
            }

            if (done >= drawn)
            {
                break;
            }
        }

        return new DotMarks([.. from], [.. burned]);
    }

    // Between each two runs of the row, the X halfway across the white, microsteps: a dot left of boundary i is in run i or before.
    private static long[] Bounds(DotPlan plan, int row, ref int[] runs)
    {
        var count = RowRuns.Find(plan.Mask.ReadRow(row), ref runs);
        var bounds = new long[Math.Max(0, count - 1)];
        for (var i = 0; i < bounds.Length; i++)
        {
            bounds[i] = (plan.Geometry.RunEdgeX(runs[(2 * i) + 1], row) + plan.Geometry.RunEdgeX(runs[(2 * i) + 2], row)) / 2;
        }

        return bounds;
    }
}

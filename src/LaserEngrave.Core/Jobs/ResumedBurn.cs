using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>What a run continued from a stop point has still to burn, and what the run it continues burned already.</summary>
/// <remarks>
/// A continued run burns the moves from its stop point (the move there from <see cref="RunStopPoint.ResumeXMicrosteps"/>
/// when it stopped inside a burn run), so the pixels covered only by the moves before it are the stopped run's: a check
/// of the continued run's burn expects them neither burned nor missing (issue 23: a continued run reported them missing).
/// </remarks>
public static class ResumedBurn
{
    /// <summary>The pixels of <paramref name="job"/> burned before <paramref name="stop"/> and not burned again from it.</summary>
    public static BitMask BurnedBefore(PreparedJob job, RunStopPoint stop)
    {
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(stop);
        var plan = job.Plan;
        var before = new BitMask(job.Mask.Width, job.Mask.Height);
        var after = new BitMask(job.Mask.Width, job.Mask.Height);
        long index = 0;
        if (job.Dots is { } dots)
        {
            // A dot run's stop point is the index of the program's first dot not fired.
            foreach (var step in dots.Program().Steps())
            {
                var column = Column(plan, step.Row, step.X, 0);
                (step.Index < stop.MoveIndex ? before : after)[column, step.Row] = true;
            }
        }
        else
        {
            foreach (var move in plan.Moves())
            {
                if (move.Kind == MoveKind.Burn && move.X0 != move.X1)
                {
                    if (index == stop.MoveIndex && stop.ResumeXMicrosteps is { } resumeX)
                    {
                        Mark(before, plan, move, move.X0, resumeX);
                        Mark(after, plan, move, resumeX, move.X1);
                    }
                    else
                    {
                        Mark(index < stop.MoveIndex ? before : after, plan, move, move.X0, move.X1);
                    }
                }

                index++;
            }
        }

        Clear(before, after);
        return before;
    }

    /// <summary>The mask a continued run is checked against: the job's black pixels less those the stopped run burned.</summary>
    public static BitMask StillToBurn(PreparedJob job, RunStopPoint stop)
    {
        var expected = job.Mask.Clone();
        var burned = BurnedBefore(job, stop);
        Clear(expected, burned);
        return expected;
    }

    // Clears in `mask` every pixel set in `bits` (masks of the same size).
    private static void Clear(BitMask mask, BitMask bits)
    {
        for (var y = 0; y < mask.Height; y++)
        {
            var m = mask.Row(y);
            var b = bits.ReadRow(y);
            for (var w = 0; w < m.Length; w++)
            {
                m[w] &= ~b[w];
            }
        }
    }

    // The columns a burn covers between two X positions along it (either way round).
    private static void Mark(BitMask mask, RasterPlan plan, in Move burn, long from, long to)
    {
        var offset = burn.X1 > burn.X0 ? 0 : StageUnitsOffset(plan);
        var (lo, hi) = from < to ? (from, to) : (to, from);
        if (hi - lo < 1)
        {
            return;
        }

        // A half microstep inside each end: the pixel the burn enters and the one it leaves, not their neighbours.
        var first = Column(plan, burn.Row, lo + 0.5, offset);
        var last = Column(plan, burn.Row, hi - 0.5, offset);
        for (var c = first; c <= last; c++)
        {
            mask[c, burn.Row] = true;
        }
    }

    private static double StageUnitsOffset(RasterPlan plan) =>
        Geometry.StageUnits.UmToMicrosteps(plan.ScanOffsetUm, plan.Geometry.MicrostepUm);

    // The column whose run edge is the last at or before x (edges grow with the column: a binary search).
    private static int Column(RasterPlan plan, int row, double x, double offset)
    {
        int lo = 0, hi = plan.Geometry.WidthPx;
        while (lo < hi)
        {
            var mid = (lo + hi + 1) / 2;
            if (plan.Geometry.RunEdgeX(mid, row, offset) <= x)
            {
                lo = mid;
            }
            else
            {
                hi = mid - 1;
            }
        }

        return Math.Clamp(lo, 0, plan.Geometry.WidthPx - 1);
    }
}

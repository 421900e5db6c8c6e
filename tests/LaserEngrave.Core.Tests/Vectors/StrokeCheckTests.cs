using System.Globalization;
using System.Text;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>The stroke's model checked by its motion, piece by piece, instead of every 0.25 ms.</summary>
public class StrokeCheckTests
{
    private static readonly TimedSwitching Timing = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MicrostepUm);

    /// <summary>
    /// A straight path along X; the X axis stands in it while Y is sent a speed and stopped again 0.08 ms later, all
    /// between two of the old 0.25 ms samples: Y leaves the path and is back (rounded to its microstep at rest) before the
    /// next sample. The old check saw 0 at every sample; the check by motion finds the excursion.
    /// </summary>
    [Fact]
    public void Run_ExcursionBetweenTheOldSamples_Caught()
    {
        var ideal = new StrokeProfile([(0, 0), (1000, 0), (2000, 0), (3000, 0)], 1000, 1_000_000);
        const double on = 1.5, off = 1.501, acceleration = 1_000_000, limit = 0.001;
        var ys = new List<AxisCommand>
        {
            new(on + 0.00030, VectorAxis.Y, AxisCommandKind.Speed, 100),
            new(on + 0.00038, VectorAxis.Y, AxisCommandKind.Stop),
        };

        var check = StrokeCheck.Run(ideal, [], ys, new StagePoint(1500, 0), on, off, acceleration, limit, speedTolerance: 10, window: 500, pathStart: 1000, pathEnd: 2000);

        // Accelerating 0.08 ms and braking as long: a * t^2 = 1e6 * (8e-5)^2 = 0.0064 microsteps at the top.
        Assert.InRange(check.Largest, 0.0064 - 1e-6, 0.0064 + 1e-3);
        Assert.Single(check.Worst);
        Assert.Equal(0, OldSampledLargest(ideal, ys, new StagePoint(1500, 0), on, off, acceleration));
    }

    [Fact]
    public void Run_AxisStillOnThePath_NothingOver()
    {
        var ideal = new StrokeProfile([(0, 0), (1000, 0), (2000, 0), (3000, 0)], 1000, 1_000_000);

        var check = StrokeCheck.Run(ideal, [], [], new StagePoint(1500, 0), 1.5, 1.6, 1_000_000, 0.001, speedTolerance: 10, window: 500, pathStart: 1000, pathEnd: 2000);

        Assert.Equal(0, check.Largest);
        Assert.Empty(check.Worst);
    }

    /// <summary>Every stroke of a curved drawing: the model replayed every 10 µs never leaves its path further than the check found (within 1 nm).</summary>
    [Fact]
    public void Plan_CurvesAndCorners_PredictedDeviationNoLessThanDenseSampling()
    {
        var drawing = SvgReader.Parse(Svg("<circle cx=\"5\" cy=\"5\" r=\"0.5\"/><path d=\"M 1 1 C 5 1 1 9 9 9\"/><polygon points=\"2,6 3,6.2 2.4,7\"/>", 20), "m.svg");
        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(5, 5) }, MachineProfile.Default);
        var schedule = VectorMotion.Plan(plan, Timing, MachineProfile.Default);

        foreach (var stroke in schedule.Strokes)
        {
            var x = new AxisModel(stroke.RunUpStart.X, Timing.Acceleration);
            var y = new AxisModel(stroke.RunUpStart.Y, Timing.Acceleration);
            var commands = stroke.Commands.Where(c => c.Kind != AxisCommandKind.Query).ToList();
            var next = 0;
            var dense = 0.0;
            // Away from the ends, where the check also measures from the run-up and run-out (on the path's line extended).
            for (var t = stroke.LaserOnSeconds; t <= stroke.LaserOffSeconds - 0.005; t += 0.00001)
            {
                while (next < commands.Count && commands[next].AtSeconds <= t)
                {
                    var c = commands[next++];
                    if (c.Axis == VectorAxis.X)
                    {
                        x.Apply(c);
                    }
                    else
                    {
                        y.Apply(c);
                    }
                }

                x.AdvanceTo(t);
                y.AdvanceTo(t);
                if (t >= stroke.LaserOnSeconds + 0.005)
                {
                    dense = Math.Max(dense, DistanceToPolyline(x.Position, y.Position, stroke.Path.Points));
                }
            }

            Assert.True(StageUnits.MicrostepsToUm(dense, MicrostepUm) <= stroke.PredictedDeviationUm + 1e-3, $"stroke {stroke.Index}: {StageUnits.MicrostepsToUm(dense, MicrostepUm)} µm sampled, {stroke.PredictedDeviationUm} µm checked");
        }
    }

    /// <summary>
    /// 4000 sharp corners (a zigzag of 51 µm strokes): each corner is split before any stroke is built (one stroke a segment, no whole-path build to
    /// split and build again), and the planning allocates a bounded amount per stroke whatever the path's length.
    /// </summary>
    [Fact]
    public void Plan_Zigzag_EveryCornerSplitBeforeTheBuildWithinAnAllocationBound()
    {
        var points = new StringBuilder();
        for (var i = 0; i < 4001; i++)
        {
            points.Append(CultureInfo.InvariantCulture, $"{i * 0.01:0.##},{i % 2 * 0.05:0.##} ");
        }

        var drawing = SvgReader.Parse(Svg($"<polyline fill=\"none\" points=\"{points}\"/>", 50), "zigzag.svg");
        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(5, 5) }, MachineProfile.Default);

        var before = GC.GetAllocatedBytesForCurrentThread();
        var schedule = VectorMotion.Plan(plan, Timing, MachineProfile.Default);
        var perStroke = (GC.GetAllocatedBytesForCurrentThread() - before) / (double)schedule.Strokes.Count;

        Assert.Equal(4000, schedule.Strokes.Count);
        Assert.All(schedule.Strokes, s => Assert.Equal(2, s.Path.Points.Count));
        Assert.All(schedule.Strokes, s => Assert.InRange(s.PredictedDeviationUm, 0, VectorMotionOptions.Default.DeviationLimitUm));
        Assert.True(perStroke < AllocationBoundPerStroke, $"{perStroke:0} bytes allocated a stroke");
    }

    // Measured 2026-11-29 on the 50 um zigzag: about 9 kB a stroke (the model, its commands, the stroke's record); a
    // build of the whole path split and built again allocated several times that.
    private const double AllocationBoundPerStroke = 16_000;

    private static double OldSampledLargest(StrokeProfile ideal, List<AxisCommand> ys, StagePoint start, double on, double off, double acceleration)
    {
        var x = new AxisModel(start.X, acceleration);
        var y = new AxisModel(start.Y, acceleration);
        var yi = 0;
        var largest = 0.0;
        for (var t = on; t <= off; t += 0.00025)
        {
            while (yi < ys.Count && ys[yi].AtSeconds <= t)
            {
                y.Apply(ys[yi++]);
            }

            x.AdvanceTo(t);
            y.AdvanceTo(t);
            largest = Math.Max(largest, ideal.DistanceToPath(x.Position, y.Position, 1000, 2000));
        }

        return largest;
    }

    private static double DistanceToPolyline(double x, double y, IReadOnlyList<StagePoint> points)
    {
        var best = double.PositiveInfinity;
        for (var i = 1; i < points.Count; i++)
        {
            best = Math.Min(best, StrokeProfile.SegmentDistance(x, y, points[i - 1].X, points[i - 1].Y, points[i].X, points[i].Y));
        }

        return best;
    }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Vectors;

/// <summary>The strokes of two axes streaming their speeds: one command a slot, gentle curves in one stroke, sharp corners split.</summary>
public class VectorMotionTests
{
    private static readonly TimedSwitching Timing = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MicrostepUm);

    private static VectorSchedule Schedule(string body, double originMm = 5, VectorMotionOptions? options = null)
    {
        var drawing = SvgReader.Parse(Svg(body, 20), "m.svg");
        var plan = VectorPlanner.Plan(drawing, new VectorOptions { Origin = new OriginMm(originMm, originMm) }, MachineProfile.Default);
        return VectorMotion.Plan(plan, Timing, MachineProfile.Default, options);
    }

    [Fact]
    public void Plan_Circle_OneStrokeWithinTheDeviationLimit()
    {
        var schedule = Schedule("<circle cx=\"5\" cy=\"5\" r=\"0.5\"/>");

        var stroke = Assert.Single(schedule.Strokes);
        Assert.InRange(stroke.PredictedDeviationUm, 0, VectorMotionOptions.Default.DeviationLimitUm);
        Assert.True(schedule.FitsTravel);
    }

    [Fact]
    public void Plan_Hexagon_SplitAtEveryCorner()
    {
        var schedule = Schedule("<polygon points=\"6,2 8,3.1547 8,5.4641 6,6.6188 4,5.4641 4,3.1547\"/>");

        Assert.Equal(6, schedule.Strokes.Count);
        Assert.All(schedule.Strokes, s => Assert.Equal(2, s.Path.Points.Count));
        Assert.All(schedule.Strokes, s => Assert.InRange(s.PredictedDeviationUm, 0, 1));
    }

    [Fact]
    public void Plan_AnyStroke_OneCommandASlotSoTheWireNeverQueues()
    {
        var schedule = Schedule("<circle cx=\"5\" cy=\"5\" r=\"2\"/><path d=\"M 1 1 C 5 1 1 9 9 9\"/>");
        var slot = Timing.FrameSeconds + Timing.MarginSeconds;

        foreach (var stroke in schedule.Strokes)
        {
            var times = stroke.Commands.Select(c => c.AtSeconds).ToList();
            for (var i = 1; i < times.Count; i++)
            {
                Assert.True(times[i] - times[i - 1] >= slot - 1e-12, $"commands {times[i - 1]} and {times[i]} s share the wire");
            }

            Assert.Contains(stroke.Commands, c => c.Kind == AxisCommandKind.Query);
            Assert.True(stroke.LaserOnSeconds < stroke.LaserOffSeconds);
            Assert.True(stroke.NextArrivalSeconds > stroke.LaserOffSeconds);
        }
    }

    [Fact]
    public void Plan_StraightLine_BothAxesInProportion()
    {
        var schedule = Schedule("<line x1=\"1\" y1=\"1\" x2=\"4\" y2=\"2\"/>");

        var stroke = Assert.Single(schedule.Strokes);
        var cruise = stroke.Commands.Where(c => c.Kind == AxisCommandKind.Speed && c.AtSeconds > stroke.LaserOnSeconds && c.AtSeconds < stroke.LaserOffSeconds).ToList();
        var x = cruise.Where(c => c.Axis == VectorAxis.X).Select(c => c.SpeedData).DefaultIfEmpty(0).Average();
        var y = cruise.Where(c => c.Axis == VectorAxis.Y).Select(c => c.SpeedData).DefaultIfEmpty(0).Average();

        // The speed data of X and Y (only changed when they change) stay 3 : 1 as the line.
        var lastX = stroke.Commands.Last(c => c.Axis == VectorAxis.X && c.Kind == AxisCommandKind.Speed && c.AtSeconds < stroke.LaserOnSeconds).SpeedData;
        var lastY = stroke.Commands.Last(c => c.Axis == VectorAxis.Y && c.Kind == AxisCommandKind.Speed && c.AtSeconds < stroke.LaserOnSeconds).SpeedData;
        Assert.InRange((double)lastX / lastY, 2.95, 3.05);
        Assert.InRange(stroke.PredictedDeviationUm, 0, 0.1);
        Assert.True(x == 0 || Math.Abs(x - lastX) <= 1);
        Assert.True(y == 0 || Math.Abs(y - lastY) <= 1);
    }

    [Fact]
    public void Plan_StopAtEveryVertex_OneStrokeASegmentAndSlower()
    {
        const string circle = "<circle cx=\"5\" cy=\"5\" r=\"0.5\"/>";
        var smooth = Schedule(circle);
        var stops = Schedule(circle, options: new VectorMotionOptions { StopAtEveryVertex = true });

        Assert.Equal(smooth.Strokes.Single().Path.Points.Count - 1, stops.Strokes.Count);
        Assert.True(stops.EstimatedSeconds > 3 * smooth.EstimatedSeconds);
    }

    [Fact]
    public void SecondsFrom_LaterStrokes_LessTimeAndTheWholeIsTheEstimate()
    {
        var schedule = Schedule("<rect x=\"1\" y=\"1\" width=\"2\" height=\"2\"/><circle cx=\"7\" cy=\"7\" r=\"1\"/>");

        Assert.Equal(schedule.EstimatedSeconds, schedule.SecondsFrom(0), 12);
        for (var k = 1; k <= schedule.Strokes.Count; k++)
        {
            Assert.True(schedule.SecondsFrom(k) < schedule.SecondsFrom(k - 1));
        }
    }

    [Fact]
    public void Plan_PathTooShortToSwitch_LeftOutWithAWarning()
    {
        var schedule = Schedule("<line x1=\"1\" y1=\"1\" x2=\"1.003\" y2=\"1\"/><line x1=\"2\" y1=\"2\" x2=\"4\" y2=\"2\"/>");

        Assert.Single(schedule.Strokes);
        Assert.Contains(schedule.Warnings, w => w.Contains("1 path(s) shorter than", StringComparison.Ordinal));
    }

    [Fact]
    public void Plan_DrawingAtTheTravelsEdge_DoesNotFitForItsRunUp()
    {
        var schedule = Schedule("<line x1=\"0\" y1=\"0\" x2=\"3\" y2=\"0\"/>", originMm: 0);

        Assert.False(schedule.FitsTravel);
        Assert.Contains(schedule.Warnings, w => w.Contains("travel ends", StringComparison.Ordinal));
    }
}

using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A stroke under way alone (<see cref="StrokeUnderWay"/>): when its switchings are written, moved by where the stage was found.</summary>
public class StrokeUnderWayTests
{
    [Fact]
    public void OnWrite_StageFoundBehindItsPlan_WritesTheSwitchOnThatMuchLater()
    {
        var s = Stroke(out var burn);
        var planned = s.OnWrite(burn.X0);

        s.Shift = 0.002;

        Assert.Equal(planned + 0.002, s.OnWrite(burn.X0), 9);
    }

    [Fact]
    public void OffWrite_ARun_WrittenItsAdvanceAndLeadBeforeItsExitEdge()
    {
        var s = Stroke(out var burn);
        var timing = s.Timing;

        Assert.Equal(s.Times.Arrival + s.Stroke.TimeAt(burn.X1) - timing.OffAdvanceSeconds - timing.OffLeadSeconds, s.OffWrite(burn.X1), 12);
        Assert.True(s.OffWrite(burn.X1) > s.OnWrite(burn.X0), "a run's switch-off is written after its switch-on");
    }

    [Fact]
    public void FlownAfter_TheLastRunOfAStroke_IsNotFlown()
    {
        var s = Stroke(out _);
        var (last, _) = s.Stroke.RunAt(s.Stroke.RunCount - 1);

        Assert.False(s.FlownAfter(last.X1));
    }

    // The first stroke with a burn run of the QR job's timed program, at 1 s on the run's clock.
    private static StrokeUnderWay Stroke(out Move burn)
    {
        var program = TestJobs.FromAsset("qr-code.bmp", 2, PlanOptions.Default, ProcessSettings.Default).Program();
        var stroke = program.Steps().Select(s => s.Stroke).First(s => s is { RunCount: > 0 })!;
        burn = stroke.RunAt(0).Move;
        var timing = program.Timing!;
        var times = new StrokeTimes(null, 1.0, 1.5);
        var watched = new ReplyWatch.Watched(Task.CompletedTask, 1.5, "the end of a stroke (X)");
        return new StrokeUnderWay(stroke, timing, times, new StrokeCut.Stroke(stroke.StartX, stroke.Direction, stroke.EndX, stroke.Plan))
        {
            End = watched,
            EndDeadline = watched.Deadline,
            Earlier = [],
            Poll = null,
            MoveStamped = 1.0,
        };
    }
}

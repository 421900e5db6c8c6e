using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The cut pixel of a timed run's stop worked out alone (<see cref="StrokeCut"/>), from a real plan's first stroke.</summary>
public class StrokeCutTests
{
    private const double Origin = 10;

    [Fact]
    public void Cut_OffConfirmedMidRun_ResumesAtThePixelTheLaserWentOffIn()
    {
        var (plan, timing, stroke, burn, index) = FirstStroke();
        var cut = Started(stroke, burn, index);

        // The fault's switch-off took effect halfway along the burn run (its lead after it left, less the jitter).
        cut.FaultOffSent(Origin + stroke.TimeAt((burn.X0 + burn.X1) / 2) - timing.OffLeadSeconds + timing.GateJitterSeconds);
        var stop = cut.Cut(new RunStopPoint(burn.Row, index), timing, plan, offConfirmed: true, 1000, null, _ => false);

        var resumeX = Assert.IsType<long>(stop.ResumeXMicrosteps);
        var pixel = Assert.IsType<PixelIndex>(stop.CutPixel);
        Assert.InRange(resumeX, Math.Min(burn.X0, burn.X1), Math.Max(burn.X0, burn.X1));
        Assert.Equal(burn.Row, pixel.Row);
        Assert.False(stop.OffByGateWatchdog);

        // X's stop never answered: the resumed run must find X at the stroke's end before it trusts the motion.
        Assert.Equal(stroke.EndX, stop.ExpectedXMicrosteps);
    }

    [Fact]
    public void Cut_XStoppedElsewhereThanItsMotion_LeavesTheStopAsItIs()
    {
        var (plan, timing, stroke, burn, index) = FirstStroke();
        var cut = Started(stroke, burn, index);
        var written = Origin + stroke.TimeAt((burn.X0 + burn.X1) / 2);
        cut.FaultOffSent(written);

        // Found far from where braking from the burn speed would have put it: the motion is not to be trusted.
        cut.Stopped(written, stroke.StartX, timing);
        var stop = new RunStopPoint(burn.Row, index);

        Assert.Same(stop, cut.Cut(stop, timing, plan, offConfirmed: true, 1000, null, _ => false));
    }

    [Fact]
    public void Cut_SwitchOnRefused_LeavesTheStopAsItIs()
    {
        var (plan, timing, stroke, burn, index) = FirstStroke();
        var cut = Started(stroke, burn, index);
        cut.FaultOffSent(Origin + stroke.TimeAt((burn.X0 + burn.X1) / 2));
        var stop = new RunStopPoint(burn.Row, index);

        Assert.Same(stop, cut.Cut(stop, timing, plan, offConfirmed: true, 1000, null, _ => true));
    }

    [Fact]
    public void Cut_NoRunBurning_LeavesTheStopAsItIs()
    {
        var (plan, timing, stroke, burn, index) = FirstStroke();
        var cut = Started(stroke, burn, index);
        cut.NotBurning();
        cut.FaultOffSent(Origin + stroke.TimeAt((burn.X0 + burn.X1) / 2));
        var stop = new RunStopPoint(burn.Row, index);

        Assert.Same(stop, cut.Cut(stop, timing, plan, offConfirmed: true, 1000, null, _ => false));
    }

    private static StrokeCut Started(StrokeStep stroke, Move burn, long index)
    {
        var cut = new StrokeCut();
        cut.Started(new StrokeCut.Stroke(stroke.StartX, stroke.Direction, stroke.EndX, stroke.Plan) { Origin = Origin });
        cut.Burning(burn, index, Task.CompletedTask);
        return cut;
    }

    private static (RasterPlan Plan, TimedSwitching Timing, StrokeStep Stroke, Move Burn, long Index) FirstStroke()
    {
        var job = TestJobs.FromMask(TestJobs.Mask("################"), 4, new PlanOptions());
        var program = job.Program();
        var stroke = program.Steps().Select(s => s.Stroke).First(s => s is not null)!;
        var (burn, index) = stroke.RunAt(0);
        return (job.Plan, Assert.IsType<TimedSwitching>(program.Timing), stroke, burn, index);
    }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class TimedSwitchingTests
{
    private static readonly TimedSwitching Defaults = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);

    [Fact]
    public void RunUp_IsTheRampPlusTheTimeToSeeTheStageMovingAndSwitchOn()
    {
        var t = Defaults;
        var ramp = t.BurnSpeed / t.Acceleration;
        var expected = (t.BurnSpeed * t.BurnSpeed / (2 * t.Acceleration)) + (t.BurnSpeed * (t.FirstEdgeSeconds - ramp));

        Assert.Equal(Math.Ceiling(expected), t.RunUpMicrosteps);
        Assert.True(t.FirstEdgeSeconds >= t.PollReplySeconds + t.OnLeadSeconds, "the switch-on leaves only after the position query is answered");
        Assert.Equal(Math.Ceiling(t.BurnSpeed * t.BurnSpeed / (2 * t.Acceleration)), t.RunOutMicrosteps);
    }

    [Fact]
    public void EdgeGuard_CoversBothLatencySpreadsSoNoPulseLandsOutside()
    {
        var profile = MachineProfile.Default with { Latency = new LatencyProfile { StageJitterMs = 2, GateJitterMs = 3, GateProcessingJitterMs = 1 } };
        var t = TimedSwitching.For(ProcessSettings.Default, profile, profile.X.MicrostepUm);

        Assert.True(t.EdgeGuardSeconds > 0.006, $"{t.EdgeGuardSeconds}");
        Assert.Equal(t.EdgeGuardSeconds, t.OffAdvanceSeconds);
        Assert.Equal(Math.Max(t.HalfPulseSeconds, t.EdgeGuardSeconds), t.OnDelaySeconds);
    }

    [Theory]
    [InlineData(1, true)]
    [InlineData(3, false)]
    [InlineData(8, false)]
    public void CrossesGap_ShortGapsAtTheBurnSpeedLongOnesByATravel(int pixelsOf122Um, bool crossed)
    {
        var gap = (long)Math.Round(pixelsOf122Um * 121.95 / Defaults.MicrostepUm);

        Assert.Equal(crossed, Defaults.CrossesGap(gap));
    }

    [Fact]
    public void Timeline_AMoveArrivesAMarginAfterTheMotionBeforeItAndASpeedChangeRidesTheBraking()
    {
        var t = Defaults;
        var timeline = new MotionTimeline(t, 0, t.TravelSpeedData);

        var first = timeline.Stroke(20_000, 0.03, 1.5);
        var travel = timeline.Travel(5_000, 0);
        var second = timeline.Stroke(20_000, 0.03, 1.5);

        Assert.True(travel.XArrival >= first.End + t.MarginSeconds - 1e-12);
        Assert.True(travel.SpeedArrival < first.End, "the travel speed is set while the stroke brakes");
        Assert.True(travel.SpeedArrival > first.End - (t.BurnSpeed / t.Acceleration), "but only once it brakes");
        Assert.True(second.Arrival >= travel.XEnd + t.MarginSeconds - 1e-12);
        Assert.True(second.SpeedArrival < travel.XEnd);
    }

    [Fact]
    public void Timeline_NothingArrivesBeforeACommandCanGetThere()
    {
        var t = Defaults;
        var timeline = new MotionTimeline(t, 10, t.TravelSpeedData);

        var stroke = timeline.Stroke(20_000, 0.03, 1.5);

        Assert.True(stroke.SpeedArrival >= 10 + t.StageCommandSeconds - 1e-12);
        Assert.True(stroke.Arrival >= stroke.SpeedArrival + t.FrameSeconds - 1e-12);
    }

    [Fact]
    public void Timeline_ATravelLeftLate_MovesBothAxesEndsAndTheNextStrokeLater()
    {
        var t = Defaults;
        var onTime = new MotionTimeline(t, 0, t.TravelSpeedData);
        var late = new MotionTimeline(t, 0, t.TravelSpeedData);
        onTime.Stroke(20_000, 0.03, 1.5);
        late.Stroke(20_000, 0.03, 1.5);
        onTime.Travel(-20_000, 5_000);
        late.Travel(-20_000, 5_000);

        late.Delay(0.040, travel: true);

        Assert.Equal(onTime.XFree + 0.040, late.XFree, 9);
        Assert.Equal(onTime.YFree + 0.040, late.YFree, 9);
        var next = late.Stroke(20_000, 0.03, 1.5);
        var planned = onTime.Stroke(20_000, 0.03, 1.5);
        Assert.True(next.Arrival >= planned.Arrival + 0.040 - 1e-9, "the next stroke waits for the late travel's ends");
    }
}

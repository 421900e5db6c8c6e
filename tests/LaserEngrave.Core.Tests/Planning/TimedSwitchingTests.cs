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
    [InlineData(20)]
    [InlineData(5)]
    public void PixelTooShort_NamesThePitchTheUserSetNotTheWholeMicrostepsBelowIt(double pitchUm)
    {
        var t = TimedSwitching.For(ProcessSettings.Default with { BurnSpeedMmPerS = 4 }, MachineProfile.Default, MachineProfile.Default.X.MicrostepUm);
        var pixel = (long)Math.Floor(pitchUm / t.MicrostepUm);

        var problem = t.PixelTooShort(pixel, pitchUm);

        Assert.NotNull(problem);
        Assert.StartsWith($"at a pitch of {pitchUm} µm a pixel lasts ", problem, StringComparison.Ordinal);
        Assert.DoesNotContain("a pixel of", problem, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(1, true)]
    [InlineData(3, true)]
    [InlineData(8, true)]
    [InlineData(400, true)]
    public void CrossesGap_FlownGapsBeatAStopGoTravel(int pixelsOf122Um, bool crossed)
    {
        var gap = (long)Math.Round(pixelsOf122Um * 121.95 / Defaults.MicrostepUm);

        Assert.Equal(crossed, Defaults.CrossesGap(gap));
    }

    [Fact]
    public void Timeline_AMoveArrivesAMarginAfterTheMotionBeforeItAndASpeedChangeRidesTheBraking()
    {
        var t = Defaults;
        var timeline = new MotionTimeline(t, 0, t.TravelSpeedData);

        var first = timeline.Stroke(t.Stroke(20_000, []), 0.03, 1.5);
        var travel = timeline.Travel(5_000, 0);
        var second = timeline.Stroke(t.Stroke(20_000, []), 0.03, 1.5);

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

        var stroke = timeline.Stroke(t.Stroke(20_000, []), 0.03, 1.5);

        Assert.True(stroke.SpeedArrival >= 10 + t.StageCommandSeconds - 1e-12);
        Assert.True(stroke.Arrival >= stroke.SpeedArrival + t.FrameSeconds - 1e-12);
    }

    [Fact]
    public void Fly_ShortGapNotFlownOnePixelFlownLongerGapsGainMore()
    {
        var t = Defaults;
        var pixel = (long)Math.Round(121.95 / t.MicrostepUm);

        Assert.Null(t.Fly(pixel / 4));
        var one = Assert.NotNull(t.Fly(pixel));
        var three = Assert.NotNull(t.Fly(3 * pixel));

        Assert.True(one.GainMicrosteps > 0);
        Assert.True(three.GainMicrosteps > one.GainMicrosteps);
        Assert.True(t.CrossSeconds(pixel) < pixel / t.BurnSpeed, "a flown pixel is crossed sooner than at the burn speed");
        Assert.True(t.CrossSeconds(3 * pixel) < t.StopGoSeconds(3 * pixel), "and a longer gap sooner than by stopping");
        Assert.True(t.CrossesGap(3 * pixel));

        // The gain of a bump held T: a T² while it never reaches the travel speed, (v_t - v_b) T once it does.
        Assert.Equal(one.GainMicrosteps, t.FlyGain(one.HoldSeconds), 9);
        Assert.Equal(t.Acceleration * 0.01 * 0.01, t.FlyGain(0.01), 9);
        Assert.Equal((t.TravelSpeed - t.BurnSpeed) * 0.5, t.FlyGain(0.5), 9);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(2)]
    [InlineData(5)]
    [InlineData(40)]
    public void StrokePlan_FlownGap_EntryCrossedWhenTheSpeedProfileSaysAndAfterTheQueryIsAnswered(int pixels)
    {
        var t = Defaults;
        var pixel = (long)Math.Round(121.95 / t.MicrostepUm);
        var exit = t.RunUpMicrosteps + (3 * pixel);
        var entry = exit + (pixels * pixel);
        var length = entry + (3 * pixel) + t.RunOutMicrosteps;

        var plan = t.Stroke(length, [(exit, entry)]);

        var bump = Assert.Single(plan.Bumps);

        // The device's own motion, integrated independently: burn speed, up at the acceleration from the speed-up's
        // arrival (never above the travel speed), down again from the speed-down's arrival, then the burn speed.
        var plain = t.Stroke(length);
        var dt = 1e-6;
        double x = exit, v = t.BurnSpeed, time = plain.TimeAt(exit);
        while (x < entry)
        {
            var a = time < bump.SpeedUpArrival ? 0
                : time < bump.SpeedDownArrival ? (v < t.TravelSpeed ? t.Acceleration : 0)
                : (v > t.BurnSpeed ? -t.Acceleration : 0);
            v = Math.Clamp(v + (a * dt), t.BurnSpeed, t.TravelSpeed);
            x += v * dt;
            time += dt;
        }

        Assert.Equal(plan.TimeAt(entry), time, 3);
        Assert.True(plan.TimeAt(entry) < plain.TimeAt(entry), "the flown gap is crossed sooner");
        Assert.Equal(plain.TimeAt(exit), plan.TimeAt(exit), 12);
        Assert.Equal(plain.Duration - (bump.GainedUpTo / t.BurnSpeed), plan.Duration, 9);

        // The query finds the stage back at the burn speed, and its answer is in before the switch-on must leave, whatever the error.
        Assert.True(bump.QueryArrival >= bump.SpeedDownArrival + t.FrameSeconds - 1e-12);
        var answered = bump.QueryArrival + (2 * t.StageJitterSeconds) + t.StageReplySeconds;
        var switchOn = plan.TimeAt(entry) + t.OnDelaySeconds - t.OnLeadSeconds - (bump.MaxErrorMicrosteps / t.BurnSpeed);
        Assert.True(answered <= switchOn, $"{answered} > {switchOn}");
        Assert.Equal(entry - (t.BurnSpeed * (plan.TimeAt(entry) - bump.QueryArrival)), bump.ExpectedOffset, 6);
    }

    [Theory]
    [InlineData(1)]
    [InlineData(3)]
    public void StrokePlan_OffsetAtJustAfterAFlownEntry_IsInTheRunNotTheGapBefore(int pixels)
    {
        var t = Defaults;
        var pixel = (long)Math.Round(121.95 / t.MicrostepUm);
        var exit = t.RunUpMicrosteps + (3 * pixel);
        var entry = exit + (pixels * pixel);
        var exit2 = entry + pixel;
        var entry2 = exit2 + pixel;
        var length = entry2 + (3 * pixel) + t.RunOutMicrosteps;

        var plan = t.Stroke(length, [(exit, entry), (exit2, entry2)]);

        Assert.Equal(2, plan.Bumps.Count);
        foreach (var edge in new[] { entry, entry2 })
        {
            // Before the fix the search found the same time inside the gap, up to the bump's gain before the edge.
            foreach (var into in new long[] { 1, 50, 200, pixel / 2 })
            {
                Assert.Equal(edge + into, plan.OffsetAt(plan.TimeAt(edge + into)), 3);
            }
        }
    }

    [Fact]
    public void Burst_SizedToTheRun_EndsBeforeThePlannedSwitchOffAndItsLineTimesItself()
    {
        var t = Defaults;

        // 120.4 ms at 1 kHz: pulses at 0, 1, ..., 120 ms; the one due at 121 ms is past the switch-off.
        Assert.Equal(121, t.PulsesWithin(0.1204));
        // A pulse due at the switch-off itself is not fired.
        Assert.Equal(120, t.PulsesWithin(0.120));
        Assert.Equal(0, t.PulsesWithin(0));
        Assert.Equal("BURST 121 1000\n", t.BurstCommand(121));

        // Written on time on a free wire, the burst fills the window exactly; written later, or behind a busy wire, it
        // counts fewer pulses so that it still stops before the switch-off (its shorter line leaves a little sooner).
        var onEffect = 1.0;
        var offEffect = 1.1204;
        var write = t.BurstWriteSeconds(onEffect, offEffect);
        Assert.Equal(onEffect - t.BurstLeadSeconds(121), write, 12);
        Assert.Equal(121, t.BurstPulses(write, double.NegativeInfinity, offEffect));
        Assert.Equal(119, t.BurstPulses(write + 0.0015, double.NegativeInfinity, offEffect));
        var busy = write + 0.005;
        var pulses = t.BurstPulses(write, busy, offEffect);
        var firing = t.GateWireFreeAfter(write, busy, t.BurstCommand(pulses).Length) + t.GateProcessingSeconds;
        Assert.True(firing + ((pulses - 1) / 1000.0) < offEffect, "its last pulse comes before the switch-off");
        Assert.True(firing + (pulses / 1000.0) >= offEffect - 1e-9, "and no pulse more would have");

        // A count whose line gains a digit is only taken if the longer line still fits.
        Assert.Equal(9, t.BurstPulses(0, double.NegativeInfinity, t.BurstLeadSeconds(9) + 0.0095));
        Assert.Null(t.RunTooLongForBurst(60_000 * 10));
        Assert.Contains("more than the 1000000", t.RunTooLongForBurst(long.MaxValue / 4), StringComparison.Ordinal);
    }

    [Fact]
    public void Timeline_ATravelLeftLate_MovesBothAxesEndsAndTheNextStrokeLater()
    {
        var t = Defaults;
        var onTime = new MotionTimeline(t, 0, t.TravelSpeedData);
        var late = new MotionTimeline(t, 0, t.TravelSpeedData);
        onTime.Stroke(t.Stroke(20_000, []), 0.03, 1.5);
        late.Stroke(t.Stroke(20_000, []), 0.03, 1.5);
        onTime.Travel(-20_000, 5_000);
        late.Travel(-20_000, 5_000);

        late.Delay(0.040, travel: true);

        Assert.Equal(onTime.XFree + 0.040, late.XFree, 9);
        Assert.Equal(onTime.YFree + 0.040, late.YFree, 9);
        var next = late.Stroke(t.Stroke(20_000, []), 0.03, 1.5);
        var planned = onTime.Stroke(t.Stroke(20_000, []), 0.03, 1.5);
        Assert.True(next.Arrival >= planned.Arrival + 0.040 - 1e-9, "the next stroke waits for the late travel's ends");
    }
}

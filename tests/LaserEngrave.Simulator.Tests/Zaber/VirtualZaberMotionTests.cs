using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Motion;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Zaber;

/// <summary>Move timing and positions against <see cref="TrapezoidProfile"/>, the estimator's model.</summary>
public class VirtualZaberMotionTests
{
    private static readonly long MaxPosition = MachineProfile.Default.X.TravelMicrosteps;

    [Theory(Timeout = 20_000)]
    [InlineData(4300, 45, 200_000)]
    [InlineData(1075, 45, 560)]
    [InlineData(100, 1, 3)]
    public async Task MoveAbsolute_Reply_ArrivesAfterFrameInPlusProfilePlusFrameOut(int speedData, int accelerationData, int distance)
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetTargetSpeed, speedData);
        await bench.RequestAsync(1, ZaberCommand.SetAcceleration, accelerationData);
        var profile = new TrapezoidProfile(distance, StageUnits.SpeedMicrostepsPerS(speedData), StageUnits.AccelerationMicrostepsPerS2(accelerationData));
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.MoveAbsolute, (int)MaxPosition - distance);
        var (reply, at) = await bench.ReceiveAsync();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveAbsolute, (int)MaxPosition - distance), reply);
        var expected = (2 * MachineBench.FrameTime) + TimeSpan.FromSeconds(profile.Duration);
        Assert.True(Math.Abs((at - sent - expected).Ticks) <= 3, $"expected {expected}, got {at - sent}");
    }

    [Fact(Timeout = 20_000)]
    public async Task ReturnCurrentPosition_MidMove_FollowsTheProfile()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(2, ZaberCommand.SetTargetSpeed, 2000);
        await bench.RequestAsync(2, ZaberCommand.SetAcceleration, 2);
        var profile = new TrapezoidProfile(300_000, StageUnits.SpeedMicrostepsPerS(2000), StageUnits.AccelerationMicrostepsPerS2(2));
        var sent = bench.Now;
        await bench.SendAsync(2, ZaberCommand.MoveRelative, -300_000);

        foreach (var afterSeconds in new[] { 0.05, 0.3, 5.0, profile.Duration - 0.1 })
        {
            var ask = sent + TimeSpan.FromSeconds(afterSeconds);
            await bench.WaitAsync(ask - bench.Now);
            var position = await bench.RequestAsync(2, ZaberCommand.ReturnCurrentPosition, 0);

            // The move starts when its frame has arrived, the query is answered when its own frame has.
            var t = (bench.Now - sent - (2 * MachineBench.FrameTime)).TotalSeconds;
            var expected = MaxPosition - profile.DistanceAt(t);
            Assert.InRange(position.Data, expected - 1, expected + 1);
        }
    }

    [Fact(Timeout = 20_000)]
    public async Task Home_Duration_UsesTheHomeSpeed()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetHomeSpeed, 8000);
        await bench.RequestAsync(1, ZaberCommand.SetAcceleration, 100);
        var profile = new TrapezoidProfile(MaxPosition, StageUnits.SpeedMicrostepsPerS(8000), StageUnits.AccelerationMicrostepsPerS2(100));
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.Home, 0);
        var (_, at) = await bench.ReceiveAsync();

        var expected = (2 * MachineBench.FrameTime) + TimeSpan.FromSeconds(profile.Duration);
        Assert.True(Math.Abs((at - sent - expected).Ticks) <= 3, $"expected {expected}, got {at - sent}");
    }

    [Fact(Timeout = 20_000)]
    public async Task SetTargetSpeed_MidMove_TheMoveFinishesSooner()
    {
        await using var bench = MachineBench.Create();
        await bench.RequestAsync(1, ZaberCommand.SetTargetSpeed, 1000);
        await bench.RequestAsync(1, ZaberCommand.SetAcceleration, 100);
        var slow = new TrapezoidProfile(200_000, StageUnits.SpeedMicrostepsPerS(1000), StageUnits.AccelerationMicrostepsPerS2(100));
        var fast = new TrapezoidProfile(200_000, StageUnits.SpeedMicrostepsPerS(4000), StageUnits.AccelerationMicrostepsPerS2(100));
        var sent = bench.Now;
        await bench.SendAsync(1, ZaberCommand.MoveRelative, -200_000);
        await bench.WaitAsync(TimeSpan.FromSeconds(2));

        var speedReply = await bench.RequestAsync(1, ZaberCommand.SetTargetSpeed, 4000);
        var (moveReply, at) = await bench.ReceiveAsync();

        Assert.Equal(new ZaberFrame(1, ZaberCommand.SetTargetSpeed, 4000), speedReply);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.MoveRelative, (int)MaxPosition - 200_000), moveReply);
        Assert.InRange((at - sent).TotalSeconds, fast.Duration, slow.Duration);
    }

    [Fact(Timeout = 20_000)]
    public async Task MoveAbsolute_BothAxesBackToBack_MoveAtTheSameTime()
    {
        await using var bench = MachineBench.Create();
        var sent = bench.Now;

        await bench.SendRawAsync([.. new ZaberFrame(1, ZaberCommand.MoveRelative, -50_000).ToBytes(), .. new ZaberFrame(2, ZaberCommand.MoveRelative, -50_000).ToBytes()]);
        var (x, xAt) = await bench.ReceiveAsync();
        var (y, yAt) = await bench.ReceiveAsync();

        // Same move, Y's command arrived one frame later: its reply is one frame behind X's, not a whole move.
        Assert.Equal((1, 2), (x.Device, y.Device));
        Assert.True(Math.Abs((yAt - xAt - MachineBench.FrameTime).Ticks) <= 3, $"Y replied {yAt - xAt} after X");
        Assert.True(xAt - sent > TimeSpan.FromSeconds(1));
    }
}

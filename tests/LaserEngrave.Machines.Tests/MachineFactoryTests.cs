using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator;

namespace LaserEngrave.Machines.Tests;

/// <summary>The one machine factory of the front ends: the twin (moved here from SimulatedMachineTests with it).</summary>
public class MachineFactoryTests
{
    [Fact(Timeout = 20_000)]
    public async Task OpenTwin_Session_TalksToTheMachineItOwnsAndClosesIt()
    {
        var ct = TestContext.Current.CancellationToken;
        var session = MachineFactory.OpenTwin(MachineProfile.Default).Session;
        var machine = Assert.IsType<SimulatedMachine>(session.Owner);

        var identity = await session.RunAsync(() => session.Stage.X.IdentifyAsync(ct));
        await session.DisposeAsync();

        Assert.Equal(1, identity.DeviceNumber);
        Assert.Same(machine.TimeProvider, session.TimeProvider);
        await machine.StageServed.WaitAsync(TimeSpan.FromSeconds(10), ct);
    }

    [Fact(Timeout = 20_000)]
    public async Task OpenTwin_Twin_IsTheInspectorOfTheTwinThatOwnsTheLinks()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var opened = MachineFactory.OpenTwin(MachineProfile.Default);
        var twin = Assert.IsType<SimulatedMachine>(opened.Session.Owner);

        await opened.Session.RunAsync(() => opened.Session.Stage.X.IdentifyAsync(ct));

        Assert.True(opened.IsSimulated);
        Assert.NotNull(opened.Twin);
        Assert.True(opened.Twin.NowSeconds > 0);
        Assert.Equal(twin.NowSeconds, opened.Twin.NowSeconds);
    }
}

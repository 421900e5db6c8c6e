using LaserEngrave.App.Web;

namespace LaserEngrave.App.Tests.Web;

public sealed class WindowLifetimeTests
{
    private static readonly TimeSpan Grace = TimeSpan.FromSeconds(10);
    private readonly ManualTimeProvider _time = new();
    private bool _runActive;
    private int _stops;

    private WindowLifetime Lifetime(TimeSpan? grace) => new(new WindowLifetimeOptions(grace), _time, () => _runActive, () => _stops++);

    [Fact]
    public void WindowClosed_NoRun_EndsAfterTheGracePeriod()
    {
        using var lifetime = Lifetime(Grace);
        lifetime.WindowOpened();

        lifetime.WindowClosed();
        _time.Advance(Grace - TimeSpan.FromSeconds(1));
        Assert.Equal(0, _stops);
        _time.Advance(TimeSpan.FromSeconds(1));

        Assert.Equal(1, _stops);
    }

    [Fact]
    public void WindowReopenedWithinGrace_KeepsRunning()
    {
        using var lifetime = Lifetime(Grace);
        lifetime.WindowOpened();
        lifetime.WindowClosed();
        _time.Advance(TimeSpan.FromSeconds(5));

        lifetime.WindowOpened();
        _time.Advance(TimeSpan.FromMinutes(10));

        Assert.Equal(0, _stops);
        Assert.False(lifetime.Ending);
    }

    [Fact]
    public void WindowClosedDuringARun_KeepsRunningUntilTheRunEndsThenGrace()
    {
        using var lifetime = Lifetime(Grace);
        lifetime.WindowOpened();
        _runActive = true;

        lifetime.WindowClosed();
        _time.Advance(TimeSpan.FromHours(2));
        Assert.Equal(0, _stops);
        _runActive = false;
        lifetime.Check();
        _time.Advance(Grace);

        Assert.Equal(1, _stops);
    }

    [Fact]
    public void NoWindowYet_NeverEnds()
    {
        using var lifetime = Lifetime(Grace);

        lifetime.Check();
        _time.Advance(TimeSpan.FromMinutes(5));

        Assert.Equal(0, _stops);
    }

    [Fact]
    public void NoGrace_ServerModeNeverEnds()
    {
        using var lifetime = Lifetime(null);
        lifetime.WindowOpened();

        lifetime.WindowClosed();
        _time.Advance(TimeSpan.FromHours(1));

        Assert.Equal(0, _stops);
    }

    [Fact]
    public void RunStartsDuringGrace_CountdownStops()
    {
        using var lifetime = Lifetime(Grace);
        lifetime.WindowOpened();
        lifetime.WindowClosed();
        Assert.True(lifetime.Ending);

        _runActive = true;
        lifetime.Check();
        _time.Advance(Grace * 3);

        Assert.Equal(0, _stops);
    }
}

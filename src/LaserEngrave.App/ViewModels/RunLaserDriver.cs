namespace LaserEngrave.App.ViewModels;

/// <summary>
/// Moves a run's drawn laser on between the engine's reports: a <see cref="LaserPace"/> over the job, asked on a timer of
/// the app's clock and after each report, each position with the instant of the machine's clock it is for; once
/// disposed it shows no laser (the machine's own position again).
/// </summary>
internal sealed class RunLaserDriver : IDisposable
{
    // The timer ticks on the pool: a tick never shows the laser again once the run has cleared it.
    private readonly Lock _lock = new();
    private readonly LaserPace _pace;
    private readonly ITimer _timer;
    private readonly Func<bool?> _moving;
    private readonly Action<PacedLaser?> _show;
    private bool _ended;

    /// <param name="pace">The run's pace, on the machine's clock.</param>
    /// <param name="timerClock">The app's clock, whose timer asks the pace every <paramref name="interval"/>.</param>
    /// <param name="moving">Whether the run is moving now (the laser drawn along its motion); null before its first report.</param>
    /// <param name="show">Where to draw the laser and for when; null clears it.</param>
    public RunLaserDriver(LaserPace pace, TimeProvider timerClock, TimeSpan interval, Func<bool?> moving, Action<PacedLaser?> show)
    {
        _pace = pace;
        _moving = moving;
        _show = show;
        _timer = timerClock.CreateTimer(_ => Tick(), null, interval, interval);
    }

    /// <summary>A progress report: in layer <paramref name="layer"/>, <paramref name="movesDone"/> of the pass's moves done, the stage at (x, y).</summary>
    public void Report(int layer, int pass, long movesDone, long x, long y)
    {
        _pace.Report(layer, pass, movesDone, x, y);
        Tick();
    }

    public void Dispose()
    {
        _timer.Dispose();
        lock (_lock)
        {
            _ended = true;
            _show(null);
        }
    }

    private void Tick()
    {
        lock (_lock)
        {
            if (!_ended && _moving() is { } moving)
            {
                var now = _pace.Now(moving, out var atSeconds);
                _show(now is { } p ? new PacedLaser(p.X, p.Y, atSeconds) : null);
            }
        }
    }
}

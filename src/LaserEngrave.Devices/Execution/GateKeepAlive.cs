using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.Devices.Execution;

/// <summary>Feeds the gate's watchdog at a fixed period while <see cref="Active"/> is set, on a <see cref="TimeProvider"/>.</summary>
/// <remarks>
/// The first failure is kept in <see cref="Fault"/> and reported through the callback, and the loop ends: a gate that
/// does not answer a keepalive cannot be trusted to answer the switch-off either, so the caller must treat it as a fault.
/// </remarks>
internal sealed class GateKeepAlive : IAsyncDisposable
{
    private readonly ILaserGate _gate;
    private readonly TimeSpan _period;
    private readonly TimeProvider _time;
    private readonly Action<Exception> _failed;
    private readonly CancellationTokenSource _stop = new();
    private readonly Task _loop;
    private volatile bool _active;
    private long _quietFrom = long.MaxValue;

    /// <param name="gate">The gate to feed.</param>
    /// <param name="period">Time between keepalives; zero or less disables the loop (watchdog off).</param>
    /// <param name="time">The clock to wait on.</param>
    /// <param name="failed">Called once, on the loop's thread, with the first failure.</param>
    public GateKeepAlive(ILaserGate gate, TimeSpan period, TimeProvider time, Action<Exception> failed)
    {
        _gate = gate;
        _period = period;
        _time = time;
        _failed = failed;
        _loop = period > TimeSpan.Zero ? TaskRunner.For(time).Start(LoopAsync) : Task.CompletedTask;
    }

    /// <summary>Whether keepalives are sent (set while the laser is on).</summary>
    public bool Active
    {
        get => _active;
        set => _active = value;
    }

    /// <summary>
    /// Clock timestamp from which no keepalive is started (<see cref="long.MaxValue"/> = none): set to just before a burn
    /// run ends, so the switch-off never waits behind a keepalive's reply while the laser stands still.
    /// </summary>
    public long QuietFrom
    {
        get => Interlocked.Read(ref _quietFrom);
        set => Interlocked.Exchange(ref _quietFrom, value);
    }

    public Exception? Fault { get; private set; }

    /// <summary>The keepalive period for a watchdog of <paramref name="watchdogMs"/> (0 = none) at <paramref name="fraction"/> of it.</summary>
    public static TimeSpan PeriodFor(int watchdogMs, double fraction) =>
        watchdogMs <= 0 ? TimeSpan.Zero : TimeSpan.FromMilliseconds(Math.Max(1, watchdogMs * Math.Clamp(fraction, 0.01, 0.9)));

    public async ValueTask DisposeAsync()
    {
        _stop.Cancel();
        try
        {
            await _loop;
        }
        catch (OperationCanceledException)
        {
            // Stopping is the normal end.
        }

        _stop.Dispose();
    }

    private async Task LoopAsync()
    {
        var token = _stop.Token;
        while (!token.IsCancellationRequested)
        {
            await Task.Delay(_period, _time, token);
            if (!_active || _time.GetTimestamp() >= QuietFrom)
            {
                continue;
            }

            try
            {
                await _gate.KeepAliveAsync(token);
            }
            catch (OperationCanceledException) when (token.IsCancellationRequested)
            {
                throw;
            }
            catch (Exception ex) when (ex is DeviceException or OperationCanceledException)
            {
                Fault = ex;
                _failed(ex);
                return;
            }
        }
    }
}

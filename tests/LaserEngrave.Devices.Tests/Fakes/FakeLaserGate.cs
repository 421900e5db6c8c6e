using System.Globalization;
using System.Text;
using System.Threading.Channels;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>A PIC laser gate speaking docs/laser-gate-protocol.md on the device end of a link; no timing, no watchdog clock.</summary>
/// <remarks>Given a <see cref="VirtualTimeProvider"/>, it runs on that clock's loop (so a test sees every reply in
/// virtual-time order, with no wall-clock waits); otherwise on the thread pool (real ports), guarded by <see cref="Eventually.Limit"/>.</remarks>
public sealed class FakeLaserGate : IAsyncDisposable
{
    private readonly ISerialLink _link;
    private readonly Channel<string> _received = Channel.CreateUnbounded<string>();
    private readonly CancellationTokenSource _stop = new();
    private readonly Task _loop;
    private readonly List<string> _log = [];
    private readonly bool _onLoop;
    private int _disposed;

    public FakeLaserGate(ISerialLink deviceEnd, TimeProvider? time = null)
    {
        _link = deviceEnd;
        _onLoop = time is VirtualTimeProvider;
        _loop = TaskRunner.For(time ?? TimeProvider.System).Start(LoopAsync);
    }

    public int FrequencyHz { get; set; }

    public int WatchdogMs { get; set; }

    public bool Tripped { get; set; }

    /// <summary>Overrides the answer: return null to answer normally, "" to stay silent, or the exact bytes to send.</summary>
    public Func<string, string?>? Intercept { get; set; }

    public string Firmware { get; set; } = "PICGATE 1.0";

    /// <summary>Every line received so far, in order.</summary>
    public List<string> AllReceived()
    {
        lock (_log)
        {
            return [.. _log];
        }
    }

    /// <summary>Waits for the next line from the host.</summary>
    public async Task<string> NextAsync() => _onLoop ? await _received.Reader.ReadAsync() : await _received.Reader.ReadAsync().AsTask().Within();

    public Task SendRawAsync(string text) => _link.WriteAsync(Encoding.ASCII.GetBytes(text), CancellationToken.None).AsTask();

    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        _stop.Cancel();
        await _link.DisposeAsync();
        await (_onLoop ? _loop : _loop.Within());
        _stop.Dispose();
    }

    private async Task LoopAsync()
    {
        var buffer = new byte[256];
        var line = new StringBuilder();
        while (true)
        {
            int n;
            try
            {
                n = await _link.ReadAsync(buffer, _stop.Token);
            }
            catch (Exception ex) when (ex is OperationCanceledException or IOException)
            {
                return;
            }

            if (n == 0)
            {
                return;
            }

            for (var i = 0; i < n; i++)
            {
                var c = (char)buffer[i];
                if (c == '\n')
                {
                    await OnLineAsync(line.ToString().TrimEnd('\r'));
                    line.Clear();
                }
                else
                {
                    line.Append(c);
                }
            }
        }
    }

    private async Task OnLineAsync(string line)
    {
        var reply = Intercept?.Invoke(line) ?? Answer(line) + "\n";
        lock (_log)
        {
            _log.Add(line);
        }

        _received.Writer.TryWrite(line);
        if (reply.Length > 0)
        {
            try
            {
                await SendRawAsync(reply);
            }
            catch (IOException)
            {
                // The host end is gone.
            }
        }
    }

    private string Answer(string line)
    {
        var words = line.Split(' ', StringSplitOptions.RemoveEmptyEntries);
        if (words.Length == 0)
        {
            return "ERR 1 UNKNOWN";
        }

        int Number(int index) => int.Parse(words[index], CultureInfo.InvariantCulture);
        switch (words[0])
        {
            case "*IDN?":
                return "OK " + Firmware;
            case "FREQ" when words.Length == 2:
                var hz = Number(1);
                if (hz is < 0 or > 100000)
                {
                    return "ERR 2 RANGE";
                }

                FrequencyHz = hz;
                return $"OK FREQ {hz}";
            case "OFF":
                FrequencyHz = 0;
                return "OK FREQ 0";
            case "STATE?":
                var state = $"OK STATE {FrequencyHz} {(FrequencyHz > 0 ? "ON" : "OFF")} WDOG {WatchdogMs}{(Tripped ? " TRIPPED" : string.Empty)}";
                Tripped = false;
                return state;
            case "WDOG" when words.Length == 2:
                WatchdogMs = Number(1);
                return $"OK WDOG {WatchdogMs}";
            case "PING":
                return "OK PONG";
            case "BURST" when words.Length == 3:
                return $"OK BURST {Number(1)}";
            default:
                return "ERR 1 UNKNOWN";
        }
    }
}

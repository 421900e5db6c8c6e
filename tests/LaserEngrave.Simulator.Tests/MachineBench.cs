using System.Text;
using System.Threading.Channels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests;

/// <summary>An in-process simulated machine driven with raw bytes: what a host would write, and what it reads back, with virtual arrival times.</summary>
/// <remarks>Each call is one operation on the simulation's loop: virtual time moves while a call waits and stands still between calls.</remarks>
internal sealed class MachineBench : IAsyncDisposable
{
    /// <summary>Time on the wire of one 6-byte frame at 9600 baud 8N1.</summary>
    public static readonly TimeSpan FrameTime = TimeSpan.FromTicks(62_500);

    private readonly Channel<(byte[] Bytes, TimeSpan At)> _frames = Channel.CreateUnbounded<(byte[], TimeSpan)>();
    private readonly Channel<(string Line, TimeSpan At)> _lines = Channel.CreateUnbounded<(string, TimeSpan)>();
    private readonly CancellationTokenSource _stop = new();
    private readonly long _origin;
    private readonly Task _stagePump;
    private readonly Task _laserPump;

    private MachineBench(SimulatedMachine machine)
    {
        Machine = machine;
        _origin = machine.TimeProvider.GetTimestamp();
        _stagePump = machine.Loop!.Start(() => PumpFramesAsync(machine.StageLink));
        _laserPump = machine.Loop!.Start(() => PumpLinesAsync(machine.LaserLink));
    }

    public SimulatedMachine Machine { get; }

    public TimeProvider Time => Machine.TimeProvider;

    /// <summary>Virtual time since the bench started.</summary>
    public TimeSpan Now => Time.GetElapsedTime(_origin);

    /// <summary>A bench whose links take the wire time only (no adapter latency, no gate processing), unless <paramref name="options"/> say otherwise.</summary>
    public static MachineBench Create(SimulatorOptions? options = null, MachineProfile? profile = null) =>
        new(SimulatedMachine.CreateInProcess(profile ?? MachineProfile.Default, options ?? WireOnly));

    /// <summary>Simulator options with the latency model switched off, so that times are whole frames on the wire.</summary>
    public static SimulatorOptions WireOnly { get; } = new() { AdapterLatency = LaserEngrave.Simulator.Timing.Jitter.None, GateProcessing = LaserEngrave.Simulator.Timing.Jitter.None };

    public Task SendAsync(byte device, int command, int data) =>
        SendRawAsync(new ZaberFrame(device, (ZaberCommand)command, data).ToBytes());

    public Task SendAsync(byte device, ZaberCommand command, int data) => SendAsync(device, (int)command, data);

    public Task SendRawAsync(byte[] bytes) => Machine.RunAsync(async () => await Machine.StageLink.WriteAsync(bytes, CancellationToken.None));

    /// <summary>The next stage frame and when it arrived; throws <see cref="TimeoutException"/> after <paramref name="within"/> of virtual time.</summary>
    public async Task<(ZaberFrame Frame, TimeSpan At)> ReceiveAsync(TimeSpan? within = null)
    {
        var (bytes, at) = await ReadAsync(_frames, within ?? TimeSpan.FromMinutes(10));
        return (ZaberFrame.Decode(bytes), at);
    }

    /// <summary>The next stage frame's raw bytes.</summary>
    public async Task<byte[]> ReceiveRawAsync(TimeSpan? within = null) => (await ReadAsync(_frames, within ?? TimeSpan.FromMinutes(10))).Bytes;

    /// <summary>The next stage frame, or null when none comes within <paramref name="within"/> of virtual time.</summary>
    public async Task<ZaberFrame?> TryReceiveAsync(TimeSpan within)
    {
        try
        {
            return (await ReceiveAsync(within)).Frame;
        }
        catch (TimeoutException)
        {
            return null;
        }
    }

    /// <summary>Sends a command and returns the next frame.</summary>
    public async Task<ZaberFrame> RequestAsync(byte device, ZaberCommand command, int data)
    {
        await SendAsync(device, command, data);
        return (await ReceiveAsync(TimeSpan.FromMinutes(10))).Frame;
    }

    public Task SendLineAsync(string line) => Machine.RunAsync(async () => await Machine.LaserLink.WriteAsync(Encoding.ASCII.GetBytes(line + "\n"), CancellationToken.None));

    /// <summary>The next gate reply line (without its "\n") and when it arrived.</summary>
    public Task<(string Line, TimeSpan At)> ReceiveLineAsync(TimeSpan? within = null) => ReadAsync(_lines, within ?? TimeSpan.FromSeconds(10));

    public async Task<string?> TryReceiveLineAsync(TimeSpan within)
    {
        try
        {
            return (await ReceiveLineAsync(within)).Line;
        }
        catch (TimeoutException)
        {
            return null;
        }
    }

    public async Task<string> AskAsync(string line)
    {
        await SendLineAsync(line);
        return (await ReceiveLineAsync()).Line;
    }

    /// <summary>Lets <paramref name="span"/> of virtual time pass.</summary>
    public Task WaitAsync(TimeSpan span) => Machine.RunAsync(() => Task.Delay(span, Time));

    public async ValueTask DisposeAsync()
    {
        await Machine.RunAsync(() =>
        {
            _stop.Cancel();
            return Task.CompletedTask;
        });
        await Machine.DisposeAsync();
        await Task.WhenAll(_stagePump, _laserPump).WaitAsync(TimeSpan.FromSeconds(5));
        _stop.Dispose();
    }

    private Task<T> ReadAsync<T>(Channel<T> channel, TimeSpan within) => Machine.RunAsync(() => ReadOnLoopAsync(channel, within));

    private async Task<T> ReadOnLoopAsync<T>(Channel<T> channel, TimeSpan within)
    {
        using var timeout = new CancellationTokenSource(within, Time);
        try
        {
            return await channel.Reader.ReadAsync(timeout.Token);
        }
        catch (OperationCanceledException) when (timeout.IsCancellationRequested)
        {
            throw new TimeoutException($"nothing arrived within {within}");
        }
    }

    private async Task PumpFramesAsync(ISerialLink link)
    {
        var buffer = new byte[64];
        var frame = new List<byte>();
        try
        {
            int n;
            while ((n = await link.ReadAsync(buffer, _stop.Token)) > 0)
            {
                for (var i = 0; i < n; i++)
                {
                    frame.Add(buffer[i]);
                    if (frame.Count == ZaberFrame.Length)
                    {
                        _frames.Writer.TryWrite(([.. frame], Now));
                        frame.Clear();
                    }
                }
            }
        }
        catch (OperationCanceledException)
        {
        }
        finally
        {
            _frames.Writer.TryComplete();
        }
    }

    private async Task PumpLinesAsync(ISerialLink link)
    {
        var buffer = new byte[64];
        var line = new StringBuilder();
        try
        {
            int n;
            while ((n = await link.ReadAsync(buffer, _stop.Token)) > 0)
            {
                for (var i = 0; i < n; i++)
                {
                    if (buffer[i] == '\n')
                    {
                        _lines.Writer.TryWrite((line.ToString(), Now));
                        line.Clear();
                    }
                    else
                    {
                        line.Append((char)buffer[i]);
                    }
                }
            }
        }
        catch (OperationCanceledException)
        {
        }
        finally
        {
            _lines.Writer.TryComplete();
        }
    }
}

using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>A connection wired in memory to two fake devices (1 = X, 2 = Y), on a virtual clock.</summary>
/// <remarks>
/// On a <see cref="VirtualTimeProvider"/> (the default) the connection and the fake devices run on the simulation's loop:
/// run the test's body with <see cref="RunAsync"/>. On a <c>FakeTimeProvider</c> they run on the thread pool with the
/// clock standing still, for tests that never move time.
/// </remarks>
public sealed class ZaberRig : IAsyncDisposable
{
    public const string Port = "/dev/fake-zaber";

    public ZaberRig(ZaberConnectionOptions? options = null)
        : this(new VirtualTimeProvider(), options)
    {
    }

    public ZaberRig(TimeProvider clock, ZaberConnectionOptions? options = null)
    {
        Clock = clock;
        var (host, device) = InMemorySerialLink.CreatePair(Port);
        Connection = new ZaberConnection(host, Clock, options);
        Wire = new FakeZaberChain(device, Clock, new FakeZaberDevice(1), new FakeZaberDevice(2));
        X = new ZaberBinaryDevice(Connection, 1, "X");
        Y = new ZaberBinaryDevice(Connection, 2, "Y");
        Connection.LineEvent += (_, e) =>
        {
            lock (LineEvents)
            {
                LineEvents.Add(e);
            }
        };
    }

    public TimeProvider Clock { get; }

    /// <summary>The virtual clock (only for a rig made on one).</summary>
    public VirtualTimeProvider Time => (VirtualTimeProvider)Clock;

    public ZaberConnection Connection { get; }

    public FakeZaberChain Wire { get; }

    public ZaberBinaryDevice X { get; }

    public ZaberBinaryDevice Y { get; }

    public List<ZaberLineEventArgs> LineEvents { get; } = [];

    public bool Saw(ZaberLineEvent kind)
    {
        lock (LineEvents)
        {
            return LineEvents.Any(e => e.Kind == kind);
        }
    }

    /// <summary>Runs the test's body: as one operation on the loop of a virtual clock, directly on a fake one.</summary>
    public Task RunAsync(Func<Task> body) => Clock.RunTestAsync(body);

    public async ValueTask DisposeAsync()
    {
        await Clock.RunTestAsync(async () =>
        {
            await Connection.DisposeAsync();
            await Wire.DisposeAsync();
        });
        (Clock as IDisposable)?.Dispose();
    }
}

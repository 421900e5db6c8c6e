using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>A connection on a manual clock, wired in memory to two fake devices (1 = X, 2 = Y).</summary>
public sealed class ZaberRig : IAsyncDisposable
{
    public const string Port = "/dev/fake-zaber";

    public ZaberRig(ZaberConnectionOptions? options = null)
    {
        var (host, device) = InMemorySerialLink.CreatePair(Port);
        Connection = new ZaberConnection(host, Clock, options);
        Wire = new FakeZaberChain(device, new FakeZaberDevice(1), new FakeZaberDevice(2));
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

    public ManualTimeProvider Clock { get; } = new();

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

    public async ValueTask DisposeAsync()
    {
        await Connection.DisposeAsync().AsTask().Within();
        await Wire.DisposeAsync().AsTask().Within();
    }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Tests.Fakes;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Tests.Zaber;

/// <summary>Discovery and the chain, with the connection and the fake devices on the simulation's loop: discovery waits out
/// the broadcast's quiet period on the virtual clock, which moves only once every reply has been read.</summary>
public class ZaberChainTests
{
    private static readonly CancellationToken None = CancellationToken.None;

    [Fact]
    public async Task DiscoverAsync_TwoDevices_ReportsBothWithTheirSettings()
    {
        await using var bench = new ChainBench(new FakeZaberDevice(1) { Firmware = 523 }, new FakeZaberDevice(2) { Firmware = 522 });
        bench.Devices[1].Settings[(byte)ZaberCommand.SetTargetSpeed] = 4300;

        await bench.RunAsync(async () =>
        {
            var discovery = await bench.DiscoverAsync(fixAutoReply: true);

            Assert.Equal([1, 2], discovery.Devices.Select(d => (int)d.DeviceNumber));
            var y = discovery.Find(2)!;
            Assert.Equal("Y", y.Role);
            Assert.Equal(522, y.FirmwareVersion);
            Assert.Equal(4300, y.SpeedData);
            Assert.Equal(bench.Devices[1].AccelerationData, y.AccelerationData);
            Assert.Equal(bench.Devices[1].MaximumPosition, y.MaximumPosition);
            Assert.Empty(discovery.Notes);
            Assert.Equal(4300, bench.Chain.Y.SpeedData);
        });
    }

    [Fact]
    public async Task DiscoverAsync_AutoReplyDisabled_ClearsBit0KeepingTheOthersAndSaysSo()
    {
        await using var bench = new ChainBench(new FakeZaberDevice(1) { Mode = 0x01 | 0x08 }, new FakeZaberDevice(2));

        await bench.RunAsync(async () =>
        {
            var discovery = await bench.DiscoverAsync(fixAutoReply: true);

            var x = discovery.Find(1)!;
            Assert.True(x.AutoReplyWasDisabled);
            Assert.True(x.AutoReplyFixed);
            Assert.Equal(0x08, bench.Devices[0].Mode);
            Assert.Equal(0x08, x.DeviceMode);
            var note = Assert.Single(discovery.Notes);
            Assert.Contains("device 1 (X) had auto-reply disabled", note, StringComparison.Ordinal);

            // Moves now reply.
            Assert.Equal(10, await bench.Chain.X.MoveAbsoluteAsync(10, None));
        });
    }

    [Fact]
    public async Task DiscoverAsync_AutoReplyDisabledWithoutFix_LeavesItAndSaysSo()
    {
        await using var bench = new ChainBench(new FakeZaberDevice(1), new FakeZaberDevice(2) { Mode = 0x01 });

        await bench.RunAsync(async () =>
        {
            var discovery = await bench.DiscoverAsync(fixAutoReply: false);

            Assert.Equal(0x01, bench.Devices[1].Mode);
            Assert.False(discovery.Find(2)!.AutoReplyFixed);
            Assert.Contains("device 2 (Y) has auto-reply disabled", Assert.Single(discovery.Notes), StringComparison.Ordinal);
        });
    }

    [Fact]
    public async Task DiscoverAsync_OnlyOneDeviceAnswers_NamesTheMissingAxis()
    {
        await using var bench = new ChainBench(new FakeZaberDevice(1));

        await bench.RunAsync(async () =>
        {
            var discovery = await bench.DiscoverAsync(fixAutoReply: true);

            Assert.Single(discovery.Devices);
            Assert.Contains("device 2 (Y) did not answer (found device(s) 1)", Assert.Single(discovery.Notes), StringComparison.Ordinal);
        });
    }

    [Fact]
    public async Task Chain_ProfileWithOtherNumbers_AddressesThoseDevices()
    {
        var profile = MachineProfile.Default with { X = MachineProfile.Default.X with { DeviceNumber = 3 }, Y = MachineProfile.Default.Y with { DeviceNumber = 4 } };
        await using var bench = new ChainBench(profile, new FakeZaberDevice(3), new FakeZaberDevice(4));

        await bench.RunAsync(async () =>
        {
            await bench.Chain.Y.MoveAbsoluteAsync(50, None);

            Assert.Equal(50, bench.Devices[1].Position);
            Assert.Equal("device 4 (Y)", bench.Chain.Y.Description);
        });
    }

    private sealed class ChainBench : IAsyncDisposable
    {
        public ChainBench(params FakeZaberDevice[] devices)
            : this(MachineProfile.Default, devices)
        {
        }

        public ChainBench(MachineProfile profile, params FakeZaberDevice[] devices)
        {
            var (host, device) = InMemorySerialLink.CreatePair("/dev/fake-chain");
            Devices = devices;
            Wire = new FakeZaberChain(device, Time, devices);
            Chain = new ZaberChain(new ZaberConnection(host, Time), profile);
        }

        public VirtualTimeProvider Time { get; } = new();

        public FakeZaberDevice[] Devices { get; }

        public FakeZaberChain Wire { get; }

        public ZaberChain Chain { get; }

        public Task RunAsync(Func<Task> body) => Time.RunTestAsync(body);

        /// <summary>Runs discovery on the loop: every device answers the broadcast at once, so it ends one quiet period later.</summary>
        public async Task<ZaberDiscovery> DiscoverAsync(bool fixAutoReply)
        {
            var discovery = await Chain.DiscoverAsync(fixAutoReply, None);
            Assert.Equal(Chain.Connection.Options.BroadcastQuietPeriod, Time.Elapsed);
            return discovery;
        }

        public async ValueTask DisposeAsync()
        {
            await Time.RunTestAsync(async () =>
            {
                await Chain.DisposeAsync();
                await Wire.DisposeAsync();
            });
            Time.Dispose();
        }
    }
}

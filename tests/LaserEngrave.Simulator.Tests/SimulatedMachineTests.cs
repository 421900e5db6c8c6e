using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests;

/// <summary>Whole jobs through the in-process machine, driven the way the executor drives it (PREAMBLE: executor protocol).</summary>
public class SimulatedMachineTests
{
    private const int BurnSpeedData = 1075;   // 1 mm/s
    private const int TravelSpeedData = 4300; // 4 mm/s

    [Fact(Timeout = 60_000)]
    public async Task Job_ExecutorProtocol_BurnsExactlyTheImageWithoutLaserOnTravel()
    {
        await using var bench = MachineBench.Create();
        var image = Image(["..##..#.", "#......#", ".######."]);
        var grid = new BurnGrid(20_000.4, 30_000.6, 559.93, image.Width, image.Height);

        await new MiniExecutor(bench, paper: false).RunAsync(image, grid);
        var report = bench.Machine.Recorder.Analyze(grid, image);

        Assert.True(report.Burned.ContentEquals(image), "the burned image differs from the plan");
        Assert.Equal(0, report.LaserOnTravelUm);
        Assert.Equal(0, report.RefusedMoves);
        Assert.True(report.LaserOnSeconds > 0);
    }

    [Fact(Timeout = 60_000)]
    public async Task Job_LaserOnBeforeASpeedChange_DwellsLongerThanTheTolerance()
    {
        await using var bench = MachineBench.Create();
        var image = Image(["..##..#."]);
        var grid = new BurnGrid(20_000, 30_000, 600, image.Width, image.Height);

        await new MiniExecutor(bench, paper: false).RunAsync(image, grid);
        var report = bench.Machine.Recorder.Analyze(grid, image);

        // Each burn run follows travel: FREQ's acknowledgement, then Set Target Speed and its reply, then the move:
        // 13.5 + 12.5 + 6.25 ms of laser standing still, over the 25 ms tolerance.
        Assert.Equal(2, report.DwellCount);
        Assert.InRange(report.LongestDwellSeconds, 0.030, 0.034);
    }

    [Fact(Timeout = 60_000)]
    public async Task Job_SameSpeedEverywhere_DwellStaysUnderTheTolerance()
    {
        await using var bench = MachineBench.Create();
        var image = Image(["..##..#.", "##.#.#.#"]);
        var grid = new BurnGrid(20_000, 30_000, 600, image.Width, image.Height);

        await new MiniExecutor(bench, paper: true).RunAsync(image, grid);
        var report = bench.Machine.Recorder.Analyze(grid, image);

        Assert.True(report.Burned.ContentEquals(image));
        Assert.Equal(0, report.DwellCount);
        Assert.InRange(report.LongestDwellSeconds, 0.0001, 0.025);
    }

    [Fact(Timeout = 60_000)]
    public async Task Job_OverAnHourOfMachineTime_SimulatesWithinTheTestTimeout()
    {
        await using var bench = MachineBench.Create();
        var image = Image([.. Enumerable.Repeat("########", 20)]);

        // 8 px of 1.25 mm at 0.05 mm/s: 200 s a row, 20 rows.
        var grid = new BurnGrid(10_000, 10_000, 12_598.4, image.Width, image.Height);

        await new MiniExecutor(bench, paper: true, burnSpeedData: 54).RunAsync(image, grid);

        Assert.True(bench.Now > TimeSpan.FromHours(1), $"the job took {bench.Now} of machine time");
        Assert.True(bench.Machine.Recorder.Analyze(grid, image).Burned.ContentEquals(image));
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateInProcess_RealTime_UsesTheSystemClock()
    {
        await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { RealTime = true });

        Assert.Same(TimeProvider.System, machine.TimeProvider);
        await machine.StageLink.WriteAsync(new ZaberFrame(1, ZaberCommand.EchoData, 5).ToBytes(), TestContext.Current.CancellationToken);
        var buffer = new byte[6];
        var read = 0;
        while (read < 6)
        {
            read += await machine.StageLink.ReadAsync(buffer.AsMemory(read), TestContext.Current.CancellationToken);
        }

        Assert.Equal(new ZaberFrame(1, ZaberCommand.EchoData, 5), ZaberFrame.Decode(buffer));
    }

    [Fact(Timeout = 20_000)]
    public async Task CreateInProcess_Default_UsesAVirtualClock()
    {
        await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default);

        Assert.IsType<VirtualTimeProvider>(machine.TimeProvider);
    }

    [Fact(Timeout = 20_000)]
    public async Task Attach_HostEndLinks_AreNotAvailable()
    {
        var (_, stage) = LaserEngrave.Wire.Serial.InMemorySerialLink.CreatePair();
        var (_, laser) = LaserEngrave.Wire.Serial.InMemorySerialLink.CreatePair();
        await using var machine = SimulatedMachine.Attach(stage, laser, MachineProfile.Default);

        Assert.Throws<InvalidOperationException>(() => machine.StageLink);
        Assert.Throws<InvalidOperationException>(() => machine.LaserLink);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReconnectAsync_AfterADisconnectFault_ServesFreshLinksWithTheDevicesState()
    {
        var ct = TestContext.Current.CancellationToken;
        await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { FaultSpec = "disconnect:stage:after=1" });
        var old = machine.StageLink;
        await machine.RunAsync(async () =>
        {
            await old.WriteAsync(new ZaberFrame(1, ZaberCommand.MoveAbsolute, 5000).ToBytes(), ct);
            await ReadFrameAsync(old, ct);
            await old.WriteAsync(new ZaberFrame(1, ZaberCommand.EchoData, 1).ToBytes(), ct);
            Assert.Equal(0, await old.ReadAsync(new byte[6], ct));
        });

        machine.Faults.Clear();
        await machine.RunAsync(machine.ReconnectAsync);
        var position = await machine.RunAsync(async () =>
        {
            await machine.StageLink.WriteAsync(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 0).ToBytes(), ct);
            return await ReadFrameAsync(machine.StageLink, ct);
        });

        Assert.NotSame(old, machine.StageLink);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.ReturnCurrentPosition, 5000), position);
    }

    private static async Task<ZaberFrame> ReadFrameAsync(LaserEngrave.Wire.Serial.ISerialLink link, CancellationToken ct)
    {
        var buffer = new byte[6];
        var read = 0;
        while (read < 6)
        {
            var n = await link.ReadAsync(buffer.AsMemory(read), ct);
            Assert.True(n > 0, "the link closed");
            read += n;
        }

        return ZaberFrame.Decode(buffer);
    }

    [Fact(Timeout = 20_000)]
    public async Task Dispose_HostSeesBothLinksClose()
    {
        var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default);
        var stage = machine.StageLink;
        var laser = machine.LaserLink;

        await machine.DisposeAsync();

        Assert.Equal(0, await stage.ReadAsync(new byte[6], TestContext.Current.CancellationToken));
        Assert.Equal(0, await laser.ReadAsync(new byte[6], TestContext.Current.CancellationToken));
    }

    private static BitMask Image(string[] rows)
    {
        var mask = new BitMask(rows[0].Length, rows.Length);
        for (var y = 0; y < rows.Length; y++)
        {
            for (var x = 0; x < rows[y].Length; x++)
            {
                mask[x, y] = rows[y][x] == '#';
            }
        }

        return mask;
    }

    /// <summary>The executor's protocol, in raw bytes: laser, then speed, then the moves, awaiting every reply.</summary>
    private sealed class MiniExecutor(MachineBench bench, bool paper, int burnSpeedData = BurnSpeedData)
    {
        private readonly Dictionary<byte, int> _speed = [];
        private bool _laserOn;

        public async Task RunAsync(BitMask image, BurnGrid grid)
        {
            // This executor does not send keepalives: without this a burn longer than the watchdog would be cut short.
            Assert.Equal("OK WDOG 0", await bench.AskAsync("WDOG 0"));
            foreach (byte axis in new byte[] { 1, 2 })
            {
                await ExpectAsync(axis, ZaberCommand.SetAcceleration, 45);
                await ExpectAsync(axis, ZaberCommand.Home, 0);
            }

            long x = 0, y = 0;
            for (var row = 0; row < image.Height; row++)
            {
                await LaserAsync(on: false);
                (x, y) = await MoveAsync(x, y, grid.ColumnEdge(0), grid.RowLine(row), paper ? burnSpeedData : TravelSpeedData);
                var column = 0;
                while (column < image.Width)
                {
                    var black = image[column, row];
                    var end = column;
                    while (end < image.Width && image[end, row] == black)
                    {
                        end++;
                    }

                    await LaserAsync(black);
                    (x, y) = await MoveAsync(x, y, grid.ColumnEdge(end), y, black || paper ? burnSpeedData : TravelSpeedData);
                    column = end;
                }
            }

            await LaserAsync(on: false);
        }

        private async Task LaserAsync(bool on)
        {
            if (on != _laserOn)
            {
                Assert.StartsWith("OK", await bench.AskAsync(on ? "FREQ 1000" : "OFF"), StringComparison.Ordinal);
                _laserOn = on;
            }
        }

        private async Task<(long X, long Y)> MoveAsync(long x, long y, long toX, long toY, int speed)
        {
            var axes = new List<(byte Device, long Target)>();
            if (toX != x)
            {
                axes.Add((1, toX));
            }

            if (toY != y)
            {
                axes.Add((2, toY));
            }

            foreach (var (device, _) in axes)
            {
                if (_speed.GetValueOrDefault(device) != speed)
                {
                    await ExpectAsync(device, ZaberCommand.SetTargetSpeed, speed);
                    _speed[device] = speed;
                }
            }

            foreach (var (device, target) in axes)
            {
                await bench.SendAsync(device, ZaberCommand.MoveAbsolute, (int)target);
            }

            var pending = axes.ToDictionary(a => a.Device, a => a.Target);
            while (pending.Count > 0)
            {
                var (reply, _) = await bench.ReceiveAsync();
                Assert.Equal(ZaberCommand.MoveAbsolute, reply.Command);
                Assert.True(pending.Remove(reply.Device, out var target) && target == reply.Data, $"unexpected reply {reply}");
            }

            return (toX, toY);
        }

        private async Task ExpectAsync(byte device, ZaberCommand command, int data)
        {
            var reply = await bench.RequestAsync(device, command, data);
            Assert.Equal(new ZaberFrame(device, command, command == ZaberCommand.Home ? 0 : data), reply);
        }
    }
}

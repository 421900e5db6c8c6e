using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Serial;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Wire.Serial;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Serial;

/// <summary>The twin's loaded computer: writes stalled between their stamp and the write, late reads, replies in pieces.</summary>
public class LoadedComputerTests
{
    private static readonly byte[] Echo = new ZaberFrame(1, ZaberCommand.EchoData, 5).ToBytes();

    [Fact(Timeout = 20_000)]
    public async Task StageLink_NeverLate_IsThePlainInMemoryLink()
    {
        await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { HostLateness = HostLateness.None });

        Assert.IsType<InMemorySerialLink>(machine.StageLink);
        Assert.IsType<InMemorySerialLink>(machine.LaserLink);
    }

    [Fact(Timeout = 20_000)]
    public async Task WriteAsync_StalledWrite_ReturnsLateAndItsBytesLeaveLateTheSameForTheSameSeed()
    {
        async Task<(double WriteMs, double ReplyMs)> EchoAsync(int seed)
        {
            var stalled = new HostLateness(0, 0, 0) { StallProbability = 1, StallMs = 20 };
            await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { HostLateness = stalled, Seed = seed });
            var time = machine.TimeProvider;
            return await machine.RunAsync(async () =>
            {
                var start = time.GetTimestamp();
                await machine.StageLink.WriteAsync(Echo, CancellationToken.None);
                var written = time.GetElapsedTime(start).TotalMilliseconds;
                var (_, arrival) = await ReadFrameAsync(machine.StageLink, time);
                return (written, time.GetElapsedTime(start, arrival).TotalMilliseconds);
            });
        }

        var first = await EchoAsync(4);
        var again = await EchoAsync(4);

        Assert.Equal(first, again);
        Assert.InRange(first.WriteMs, HostLateness.ShortestStallMs, 20);

        // The echo takes its wire time both ways (6.25 ms each at 9600 baud) after the stall, not from the stamp.
        Assert.InRange(first.ReplyMs, first.WriteMs + 12.5, first.WriteMs + 20);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReadStampedAsync_LateRead_ReturnsLateWithItsArrivalTimeAndTheLinkSaysBytesWait()
    {
        var late = new HostLateness(0, 0, 0) { LateReadProbability = 1, LateReadMs = 60 };
        await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { HostLateness = late });
        var time = machine.TimeProvider;

        var (heldMs, sawWaiting) = await machine.RunAsync(async () =>
        {
            await machine.StageLink.WriteAsync(Echo, CancellationToken.None);
            var buffer = new byte[6];
            var read = machine.StageLink.ReadStampedAsync(buffer, time, CancellationToken.None).AsTask();
            var waiting = false;
            while (!read.IsCompleted)
            {
                waiting |= machine.StageLink.HasUnreadBytes;
                await Task.Delay(TimeSpan.FromMilliseconds(1), time);
            }

            var stamped = await read;
            return (time.GetElapsedTime(stamped.ArrivalTimestamp).TotalMilliseconds, waiting);
        });

        Assert.InRange(heldMs, HostLateness.ShortestStallMs, 61);
        Assert.True(sawWaiting);
    }

    [Fact(Timeout = 20_000)]
    public async Task Send_ReplyPieces_TheReplyComesInTwoPiecesItsLastWhenTheWholeWouldHave()
    {
        async Task<List<(byte[] Bytes, double AtMs)>> ReadsAsync(ReplyPieces pieces)
        {
            await using var machine = SimulatedMachine.CreateInProcess(MachineProfile.Default, new SimulatorOptions { ReplyPieces = pieces });
            var time = machine.TimeProvider;
            return await machine.RunAsync(async () =>
            {
                var start = time.GetTimestamp();
                await machine.StageLink.WriteAsync(Echo, CancellationToken.None);
                var reads = new List<(byte[], double)>();
                var buffer = new byte[6];
                for (var got = 0; got < 6;)
                {
                    var read = await machine.StageLink.ReadStampedAsync(buffer, time, CancellationToken.None);
                    reads.Add((buffer[..read.Count], time.GetElapsedTime(start, read.ArrivalTimestamp).TotalMilliseconds));
                    got += read.Count;
                }

                return reads;
            });
        }

        var whole = Assert.Single(await ReadsAsync(ReplyPieces.None));
        var pieces = await ReadsAsync(new ReplyPieces(1, 3));

        Assert.Equal(2, pieces.Count);
        Assert.Equal(Echo, pieces[0].Bytes.Concat(pieces[1].Bytes));
        Assert.Equal(whole.AtMs, pieces[1].AtMs, 9);
        Assert.InRange(pieces[1].AtMs - pieces[0].AtMs, 0.001, 3 + 1e-9);
    }

    [Theory]
    [InlineData("""{ "replyPieces": { "probability": 1, "gapMs": 3 } }""", null)]
    [InlineData("""{ "replyPieces": { "probability": 2, "gapMs": 3 } }""", "replyPieces must have probability from 0 to 1")]
    [InlineData("""{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 0.01, "tailMs": 5, "stallProbability": 0.001, "stallMs": 40, "lateReadProbability": 0.002, "lateReadMs": 80 } }""", null)]
    [InlineData("""{ "hostLateness": { "typicalMs": 0.5, "tailProbability": 0.01, "tailMs": 5, "stallProbability": 0.001, "stallMs": 4000 } }""", "stallMs and lateReadMs from 0 to 1000 ms")]
    public void OptionsFile_LoadedComputer_ReadOrRefusedNamingTheField(string json, string? fragment)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            if (fragment is not null)
            {
                var ex = Assert.Throws<InvalidDataException>(() => SimulatorOptionsFile.Load(path, new SimulatorOptions()));
                Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
                return;
            }

            var options = SimulatorOptionsFile.Load(path, new SimulatorOptions());
            if (json.Contains("replyPieces", StringComparison.Ordinal))
            {
                Assert.Equal(new ReplyPieces(1, 3), options.ReplyPieces);
            }
            else
            {
                Assert.Equal(new HostLateness(0.5, 0.01, 5) { StallProbability = 0.001, StallMs = 40, LateReadProbability = 0.002, LateReadMs = 80 }, options.HostLateness);
            }
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void FrontEnd_ALoadedComputer_StallsReadsLateAndSplitsReplies()
    {
        var frontEnd = SimulatorOptions.FrontEnd;

        Assert.True(frontEnd.HostLateness.Stalls);
        Assert.True(frontEnd.HostLateness.ReadsLate);
        Assert.False(frontEnd.ReplyPieces.IsNone);
        Assert.True(new SimulatorOptions().ReplyPieces.IsNone, "the library's default keeps every reply whole");
    }

    private static async Task<(ZaberFrame Frame, long Arrival)> ReadFrameAsync(ISerialLink link, TimeProvider time)
    {
        var buffer = new byte[6];
        var got = 0;
        long arrival = 0;
        while (got < 6)
        {
            var read = await link.ReadStampedAsync(buffer.AsMemory(got), time, CancellationToken.None);
            got += read.Count;
            arrival = read.ArrivalTimestamp;
        }

        return (ZaberFrame.Decode(buffer), arrival);
    }
}

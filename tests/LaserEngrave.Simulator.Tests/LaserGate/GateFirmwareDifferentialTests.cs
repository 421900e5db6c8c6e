using System.Globalization;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Tests.LaserGate;

/// <summary>
/// The twin's gate agrees with the reference firmware: one recorded gate stream (firmware/gate/sim/differential, the
/// QR sample's gate lines with their arrival times) fed into the twin's gate, every burst's pulse count and first-pulse
/// time compared with what the ATmega328P image did with the same stream in simavr (the committed result, which
/// <c>make -C firmware/gate test-differential</c> proves is still what the image does).
/// </summary>
public class GateFirmwareDifferentialTests
{
    private const double CycleHz = 16_000_000;

    /// <summary>One bit at 9600 baud: the gate's UART samples a line's last byte within it.</summary>
    private const double BitSeconds = 1.0 / 9600;

    /// <summary>
    /// qr5mm: the QR's gate lines as the twin's host wrote them, replayed in gate_sim. qr5mm-pty: the QR engraved by the
    /// host itself with the gate image on a pty in simavr (firmware/gate/sim/host-bench.sh), the lines and pulses as
    /// the image received and fired them on the wall clock (two runs: -rt with the simulated devices at real-time priority).
    /// sched: scheduled bursts (BURST n hz AFTER us, 0 to 100 ms, at 245 Hz to 100 kHz), one cancelled by OFF, one kept
    /// through a PING, one ending a burst under way: the first pulse is the gate's own timer's, so the twin and the
    /// firmware must agree on it (within one timer tick plus the UART's bit time, as for every burst).
    /// </summary>
    [Theory(Timeout = 120_000)]
    [InlineData("qr5mm", 60)]
    [InlineData("qr5mm-pty", 266)]
    [InlineData("qr5mm-pty-rt", 284)]
    [InlineData("sched", 10)]
    public async Task RecordedStream_TwinAndFirmware_SameBurstsAndFirstPulses(string name, int expectedBursts)
    {
        var folder = Path.Combine(RepositoryRoot, "firmware", "gate", "sim", "differential");
        var stream = ReadStream(Path.Combine(folder, $"{name}-gate-stream.txt"));
        var firmware = ReadFirmware(Path.Combine(folder, $"{name}-avr-bursts.txt"));

        // The stream is timed at the gate, so the twin's adapter adds nothing; its gate keeps its own (firmware) model.
        await using var bench = MachineBench.Create(new SimulatorOptions { AdapterLatency = Jitter.None, Seed = 3 });
        var byteSeconds = 10.0 / bench.Machine.Gate.BaudRate;
        var origin = bench.Machine.NowSeconds;
        foreach (var (at, text) in stream)
        {
            // Written so that its last byte arrives at the stream's instant.
            var writeAt = origin + at - ((text.Length + 1) * byteSeconds);
            var wait = writeAt - bench.Machine.NowSeconds;
            Assert.True(wait >= 0, $"line '{text}' cannot be written in time ({wait} s)");
            await WaitExactlyAsync(bench, TimeSpan.FromSeconds(wait));
            await bench.SendLineAsync(text);
        }

        await bench.WaitAsync(TimeSpan.FromSeconds(2));
        var intervals = bench.Machine.Recorder.LaserOnIntervals(bench.Machine.NowSeconds);

        var frequencyLines = stream.Select((line, index) => (line.At, line.Text, Index: index))
            .Where(l => l.Text.Split(' ')[0].ToUpperInvariant() is "FREQ" or "OFF" or "BURST").ToList();
        Assert.Equal(firmware.Count, frequencyLines.Count);
        // A train belongs to the line that started it: the last frequency line to arrive before its first pulse (the
        // firmware's side groups its pulses the same way, firmware/gate/sim/differential.py).
        var trains = frequencyLines.ToDictionary(l => l.Index, _ => new List<(double From, double To)>());
        foreach (var interval in intervals)
        {
            var owner = frequencyLines.Last(l => origin + l.At < interval.From);
            trains[owner.Index].Add(interval);
        }

        var bursts = 0;
        var pulses = 0L;
        var worst = 0.0;
        for (var k = 0; k < frequencyLines.Count; k++)
        {
            var (_, text, index) = frequencyLines[k];
            var (avrIndex, avrPulses, avrFirstCycle) = firmware[k];
            Assert.Equal(index, avrIndex);

            var words = text.Split(' ');
            var hz = words[0] == "BURST" ? int.Parse(words[2], CultureInfo.InvariantCulture) : words[0] == "FREQ" ? int.Parse(words[1], CultureInfo.InvariantCulture) : 0;
            var mine = trains[index];
            var twinPulses = mine.Sum(i => PulsesIn(i.From, i.To, hz));
            Assert.True(avrPulses == twinPulses, $"line {index} '{text}': the firmware fired {avrPulses} pulses, the twin {twinPulses}");
            if (avrFirstCycle is { } cycle)
            {
                var twinFirst = mine[0].From - origin;
                var avrFirst = cycle / CycleHz;
                var tolerance = GateFirmwareTiming.TickSeconds(hz) + BitSeconds;
                var difference = Math.Abs(twinFirst - avrFirst);
                Assert.True(difference <= tolerance,
                    $"line {index} '{text}': first pulse at {avrFirst * 1000:0.0000} ms on the firmware, {twinFirst * 1000:0.0000} ms on the twin ({difference * 1e6:0.0} µs apart)");
                worst = Math.Max(worst, difference);
                bursts++;
                pulses += avrPulses;
            }
        }

        // Every burst of the stream that fires fired on both.
        Assert.Equal(expectedBursts, bursts);
        Assert.True(pulses > 600, $"only {pulses} pulses compared");
        TestContext.Current.TestOutputHelper?.WriteLine($"{name}: {bursts} bursts, {pulses} pulses, first pulses at most {worst * 1e6:0.0} µs apart");
    }

    // Lets exactly that much virtual time pass (Task.Delay counts whole milliseconds; the stream's instants are finer).
    private static Task WaitExactlyAsync(MachineBench bench, TimeSpan span) => bench.Machine.RunAsync(async () =>
    {
        var done = new TaskCompletionSource(TaskCreationOptions.RunContinuationsAsynchronously);
        using var timer = bench.Time.CreateTimer(_ => done.TrySetResult(), null, span, Timeout.InfiniteTimeSpan);
        await done.Task;
    });

    // The twin's pulses: at the switch-on instant and every fired period after it, none at the switch-off instant.
    private static long PulsesIn(double from, double to, int hz)
    {
        if (hz <= 0)
        {
            return 0;
        }

        var period = GateFirmwareTiming.FiredPeriodSeconds(hz);
        return (long)Math.Ceiling(((to - from) / period) - 1e-6);
    }

    private static List<(double At, string Text)> ReadStream(string path) =>
        [.. File.ReadAllLines(path).Where(l => l.Length > 0 && l[0] != '#').Select(l =>
        {
            var space = l.IndexOf(' ', StringComparison.Ordinal);
            return (long.Parse(l[..space], CultureInfo.InvariantCulture) / CycleHz, l[(space + 1)..]);
        })];

    private static List<(int Index, long Pulses, long? FirstCycle)> ReadFirmware(string path) =>
        [.. File.ReadAllLines(path).Where(l => l.Length > 0 && l[0] != '#').Select(l =>
        {
            var f = l.Split(' ');
            return (int.Parse(f[0], CultureInfo.InvariantCulture), long.Parse(f[2], CultureInfo.InvariantCulture),
                f[3] == "-" ? (long?)null : long.Parse(f[3], CultureInfo.InvariantCulture));
        })];

    private static string RepositoryRoot
    {
        get
        {
            var dir = new DirectoryInfo(AppContext.BaseDirectory);
            while (dir is not null && !File.Exists(Path.Combine(dir.FullName, "LaserEngrave.sln")))
            {
                dir = dir.Parent;
            }

            return dir?.FullName ?? throw new InvalidOperationException($"LaserEngrave.sln not found above {AppContext.BaseDirectory}");
        }
    }
}

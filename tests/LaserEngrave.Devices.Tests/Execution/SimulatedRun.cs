using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Simulator;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>An in-process simulated machine with the real ZaberChain and PicLaserGate on its links, in virtual time.</summary>
internal sealed class SimulatedRun : IAsyncDisposable
{
    private readonly Func<ISerialLink, TimeProvider, ISerialLink>? _gateLink;

    private SimulatedRun(SimulatedMachine machine, Func<ISerialLink, TimeProvider, ISerialLink>? gateLink = null)
    {
        Machine = machine;
        _gateLink = gateLink;
        Connect();
    }

    public SimulatedMachine Machine { get; }

    public ZaberChain Stage { get; private set; } = null!;

    public PicLaserGate Gate { get; private set; } = null!;

    /// <summary>Every line the host wrote to the gate and every command to the stage, with its time (s on the simulator's clock).</summary>
    public List<(double Seconds, string Port, string Line)> Written { get; } = [];

    public TimeProvider Time => Machine.TimeProvider;

    public static SimulatedRun Create(SimulatorOptions? options = null, MachineProfile? profile = null) =>
        new(SimulatedMachine.CreateInProcess(profile ?? MachineProfile.Default, options));

    /// <summary>A run whose gate link passes through <paramref name="gateLink"/> (a test's stalled or held link).</summary>
    public static SimulatedRun Create(SimulatorOptions? options, Func<ISerialLink, TimeProvider, ISerialLink> gateLink) =>
        new(SimulatedMachine.CreateInProcess(MachineProfile.Default, options), gateLink);

    public RunExecutor Executor(PreparedJob job, RunOptions? options = null) => new(Stage, Gate, job, Time, options);

    public StageTestMoves TestMoves() => new(Stage, Gate, Machine.Profile, timeProvider: Time);

    /// <summary>The simulation's loop, for continuations that must run there (as the host's own code does).</summary>
    public TaskScheduler Loop => Machine.Loop!.Scheduler;

    /// <summary>Runs an operation of the host on the simulation (virtual time moves while it waits).</summary>
    public Task<T> Do<T>(Func<Task<T>> operation) => Machine.RunAsync(operation);

    /// <summary>Runs an operation that returns nothing on the simulation.</summary>
    public Task Do(Func<Task> operation) => Machine.RunAsync(operation);

    /// <summary>Clears every fault and plugs fresh links in (the machine keeps its state), as a technician would after a fault.</summary>
    public async Task RecoverAsync()
    {
        Machine.Faults.Clear();
        await Do(async () =>
        {
            await Stage.DisposeAsync();
            await Gate.DisposeAsync();
            await Machine.ReconnectAsync();

            // On the loop, so the new readers start in the same place in its queue every time.
            Connect();
        });
    }

    public BurnReport Analyze(PreparedJob job) => Machine.Recorder.Analyze(Grid(job), job.Mask);

    public static BurnGrid Grid(PreparedJob job) => BurnGrid.For(job.Plan.Geometry);

    public async ValueTask DisposeAsync()
    {
        await Do(async () =>
        {
            await Stage.DisposeAsync();
            await Gate.DisposeAsync();
        });
        await Machine.DisposeAsync();
    }

    private void Connect()
    {
        Stage = new ZaberChain(new ZaberConnection(new WrittenLink(Machine.StageLink, this, "stage"), Machine.TimeProvider), Machine.Profile);
        var gateLink = new WrittenLink(Machine.LaserLink, this, "gate");
        Gate = new PicLaserGate(_gateLink?.Invoke(gateLink, Machine.TimeProvider) ?? gateLink, Machine.Profile.Gate, Machine.TimeProvider);
    }
}

/// <summary>Jobs for the run tests: sample images and seeded random masks.</summary>
internal static class TestJobs
{
    public static readonly OriginMm Origin = new(10, 10);

    public static PreparedJob FromAsset(string name, double widthMm, PlanOptions plan, ProcessSettings? process = null) =>
        PreparedJob.Prepare(new JobSpec
        {
            ImagePath = AssetPath(name),
            Size = SizeSpec.Width(widthMm),
            Origin = Origin,
            Plan = plan,
            Process = process ?? ProcessSettings.Default,
        });

    public static PreparedJob FromMask(BitMask mask, double widthMm, PlanOptions plan, OriginMm? origin = null, ProcessSettings? process = null, MachineProfile? profile = null)
    {
        var spec = new JobSpec
        {
            Profile = profile ?? MachineProfile.Default,
            ImagePath = "mask",
            Size = SizeSpec.Width(widthMm),
            Origin = origin ?? Origin,
            Plan = plan,
            Process = process ?? ProcessSettings.Default,
        };
        var info = new ImageInfo("mask", ImageFormat.Pbm, 1, 2, mask.Width, mask.Height, 0, null, null, RowOrder.TopDown, "none", false);
        return PreparedJob.Prepare(spec, info, mask);
    }

    public static BitMask RandomMask(int seed, int width, int height, double black = 0.4)
    {
        var random = new Random(seed);
        var mask = new BitMask(width, height);
        for (var y = 0; y < height; y++)
        {
            for (var x = 0; x < width; x++)
            {
                mask[x, y] = random.NextDouble() < black;
            }
        }

        return mask;
    }

    public static BitMask Mask(params string[] rows)
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

    public static string AssetPath(string name)
    {
        var directory = new DirectoryInfo(AppContext.BaseDirectory);
        while (directory is not null && !Directory.Exists(Path.Combine(directory.FullName, "assets")))
        {
            directory = directory.Parent;
        }

        return directory is null
            ? throw new FileNotFoundException($"no assets folder above {AppContext.BaseDirectory}")
            : Path.Combine(directory.FullName, "assets", name);
    }
}

// Passes everything through, and notes what the host writes (a gate's line as text, a stage's frame in hex).
/// <summary>A link of a <see cref="SimulatedRun"/> that notes what the host writes.</summary>
internal sealed class WrittenLink(ISerialLink inner, SimulatedRun run, string port) : ISerialLink
{
    public string Name => inner.Name;

    public bool HasUnreadBytes => inner.HasUnreadBytes;

    public ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) => inner.ReadAsync(buffer, cancellationToken);

    public ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken) => inner.ReadStampedAsync(buffer, time, cancellationToken);

    public ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
    {
        var line = port == "gate" ? System.Text.Encoding.ASCII.GetString(data.Span).TrimEnd('\r', '\n') : Convert.ToHexString(data.Span);
        lock (run.Written)
        {
            run.Written.Add((run.Machine.NowSeconds, port, line));
        }

        return inner.WriteAsync(data, cancellationToken);
    }

    public ValueTask DisposeAsync() => inner.DisposeAsync();
}

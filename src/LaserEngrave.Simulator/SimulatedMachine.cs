using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Serial;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Simulator.Zaber;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Simulator;

/// <summary>The whole machine in software: the Zaber chain on one link, the laser gate on another, a burn recorder and faults.</summary>
/// <remarks>
/// In-process (<see cref="CreateInProcess"/>) the host talks to <see cref="StageLink"/> and <see cref="LaserLink"/>; in
/// virtual time (the default) host and devices run on one <see cref="SimulationLoop"/>, and every operation of the host
/// goes through <see cref="RunAsync{T}"/> (or <see cref="Wire.Scheduling.TaskRunner.For"/> with <see cref="TimeProvider"/>),
/// so the run is deterministic and as fast as the machine can compute it. With <see cref="SimulatorOptions.RealTime"/>
/// it runs on the wall clock. Attached (<see cref="Attach"/>) it serves the device ends of real ports or ptys for a host
/// in another process, always on the wall clock. Runs until disposed.
/// </remarks>
public sealed class SimulatedMachine : IAsyncDisposable
{
    /// <summary>Port name of the stage in events.</summary>
    public const string StagePort = "stage";

    /// <summary>Port name of the laser gate in events.</summary>
    public const string LaserPort = "laser";

    private readonly CancellationTokenSource _stop = new();
    private readonly SimulationClock _clock;
    private readonly VirtualTimeProvider? _virtual;
    private readonly ITaskRunner _runner;
    private readonly bool _inProcess;
    private readonly Random _random;
    private ISerialLink? _stageHost;
    private ISerialLink? _laserHost;
    private readonly Lock _tasksLock = new();
    private readonly List<Task> _tasks = [];
    private Task _stageServed = Task.CompletedTask;
    private Task _laserServed = Task.CompletedTask;
    private int _disposed;
    private int _loadedLinks;

    private SimulatedMachine(MachineProfile profile, SimulatorOptions options, bool inProcess)
    {
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(options);
        profile.Validate();
        Profile = profile;
        Options = options;
        if (inProcess && !options.RealTime)
        {
            _virtual = new VirtualTimeProvider(options.VirtualStart, options.Paced);
            TimeProvider = _virtual;
            if (!options.HostLateness.WakesOnTime)
            {
                // Its own stream, so the links' draws (and every figure without host lateness) stay as they were.
                var lateness = options.HostLateness;
                var random = new Random(unchecked(options.Seed * 7919) ^ 0x4C415445);
                _virtual.HostLateness = () => TimeSpan.FromSeconds(lateness.SampleSeconds(random));
            }
        }
        else
        {
            TimeProvider = TimeProvider.System;
        }

        _runner = TaskRunner.For(TimeProvider);
        _random = new Random(options.Seed);
        _clock = new SimulationClock(TimeProvider);
        Faults = FaultInjector.Parse(options.FaultSpec);
        Faults.Triggered += (_, rule) => Raise(rule.Target == FaultTarget.Stage ? StagePort : LaserPort, $"fault injected: {rule}");
        var x = new Motion.AxisTrajectory(StartPosition(profile.X, options, 0));
        var y = new Motion.AxisTrajectory(StartPosition(profile.Y, options, 1));
        Recorder = new BurnRecorder(x, y, profile.X.MicrostepUm, profile.Y.MicrostepUm, options.DwellTolerance, () => _clock.NowSeconds)
        {
            Z = profile.Z is { } z ? new Motion.AxisTrajectory(StartPosition(z, options, 2)) : null,
        };
        Stage = new VirtualZaberChain(profile, options, _clock, Faults, Recorder);
        Gate = new VirtualLaserGate(profile.Gate, options, _clock, Faults, Recorder);
        _inProcess = inProcess;
        if (inProcess)
        {
            _stageHost = ServeInProcessStage();
            _laserHost = ServeInProcessLaser();
        }
    }

    /// <summary>Raised for every connection event, injected fault and watchdog trip; handlers run on the simulator's threads.</summary>
    public event EventHandler<SimulatorEvent>? EventRaised;

    public MachineProfile Profile { get; }

    public SimulatorOptions Options { get; }

    /// <summary>The clock the simulator runs on; give it to the host code under test.</summary>
    public TimeProvider TimeProvider { get; }

    /// <summary>The loop that runs host and devices in virtual time; null on the wall clock.</summary>
    public SimulationLoop? Loop => _virtual?.Loop;

    /// <summary>Whether time is virtual (deterministic, as fast as it can be computed) rather than the wall clock.</summary>
    public bool IsVirtualTime => _virtual is not null;

    /// <summary>The Zaber chain (X, Y, and Z when the profile has a focus axis).</summary>
    public VirtualZaberChain Stage { get; }

    public VirtualLaserGate Gate { get; }

    public BurnRecorder Recorder { get; }

    /// <summary>The faults being injected; rules may be added or cleared while the machine runs.</summary>
    public FaultInjector Faults { get; }

    /// <summary>Seconds since the machine started, on its clock (the time base of trajectories and the recorder).</summary>
    public double NowSeconds => _clock.NowSeconds;

    /// <summary>The host's end of the stage link (in-process mode only).</summary>
    public ISerialLink StageLink => _stageHost ?? throw new InvalidOperationException("an attached simulator has no host-end stage link: the host uses the other end of the port");

    /// <summary>The host's end of the laser gate link (in-process mode only).</summary>
    public ISerialLink LaserLink => _laserHost ?? throw new InvalidOperationException("an attached simulator has no host-end laser link: the host uses the other end of the port");

    /// <summary>Completes when the stage link in use has closed.</summary>
    public Task StageServed => _stageServed;

    /// <summary>Completes when the laser link in use has closed.</summary>
    public Task LaserServed => _laserServed;

    /// <summary>Runs an operation of the host (a run, a test move, a test's steps) on the simulation: in virtual time on its loop, where time moves while the operation waits.</summary>
    public Task<T> RunAsync<T>(Func<Task<T>> operation) => _runner.Run(operation);

    /// <summary>Runs an operation of the host that returns nothing; see <see cref="RunAsync{T}"/>.</summary>
    public Task RunAsync(Func<Task> operation) => TaskRunner.Run(TimeProvider, operation);

    /// <summary>A machine on in-memory links, for tests and the app: the host uses <see cref="StageLink"/> and <see cref="LaserLink"/>.</summary>
    public static SimulatedMachine CreateInProcess(MachineProfile profile, SimulatorOptions? options = null)
    {
        return new SimulatedMachine(profile, options ?? new SimulatorOptions(), inProcess: true);
    }

    /// <summary>A machine serving the device ends of two links, e.g. ptys made by socat or real serial ports.</summary>
    public static SimulatedMachine Attach(ISerialLink stageDeviceEnd, ISerialLink laserDeviceEnd, MachineProfile profile, SimulatorOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(stageDeviceEnd);
        ArgumentNullException.ThrowIfNull(laserDeviceEnd);
        var machine = new SimulatedMachine(profile, options ?? new SimulatorOptions(), inProcess: false);
        machine.ServeStage(stageDeviceEnd);
        machine.ServeLaser(laserDeviceEnd);
        return machine;
    }

    /// <summary>Serves a new stage link, e.g. after the old port went away; the devices keep their state.</summary>
    public void ServeStage(ISerialLink deviceEnd)
    {
        ArgumentNullException.ThrowIfNull(deviceEnd);
        _stageServed = Track(StagePort, deviceEnd, log => Stage.RunAsync(deviceEnd, log, NewLatency(), _stop.Token));
    }

    /// <summary>Serves a new laser gate link; the gate keeps its state.</summary>
    public void ServeLaser(ISerialLink deviceEnd)
    {
        ArgumentNullException.ThrowIfNull(deviceEnd);
        _laserServed = Track(LaserPort, deviceEnd, log => Gate.RunAsync(deviceEnd, log, NewLatency(Options.GateProcessing ?? Jitter.None), _stop.Token));
    }

    /// <summary>
    /// In-process: closes both host links (if the host has not) and serves fresh ones, as if the cables were plugged in
    /// again after a fault; the devices keep their state. The new host ends are <see cref="StageLink"/> and <see cref="LaserLink"/>.
    /// </summary>
    public async Task ReconnectAsync()
    {
        if (!_inProcess)
        {
            throw new InvalidOperationException("an attached simulator is reconnected by serving new device ends (ServeStage, ServeLaser)");
        }

        await _stageHost!.DisposeAsync();
        await _laserHost!.DisposeAsync();
        await _stageServed;
        await _laserServed;
        _stageHost = ServeInProcessStage();
        _laserHost = ServeInProcessLaser();
    }

    /// <summary>Stops serving, closes the links and, in virtual time, stops the loop.</summary>
    public async ValueTask DisposeAsync()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        if (_virtual is not null)
        {
            // On the loop, so the sessions wind down in the same order every time; nothing there waits on the wall clock.
            await _virtual.Run(async () =>
            {
                await StopServingAsync();
                return true;
            });
            _virtual.Dispose();
        }
        else
        {
            await StopServingAsync();
        }

        _stop.Dispose();
    }

    private async Task StopServingAsync()
    {
        _stop.Cancel();
        Task[] tasks;
        lock (_tasksLock)
        {
            tasks = [.. _tasks];
        }

        if (_virtual is not null)
        {
            await Task.WhenAll(tasks);
        }
        else
        {
            // A blocking stream (a pty file) may not notice the cancellation until its peer goes away: do not wait for ever.
            await Task.WhenAny(Task.WhenAll(tasks), Task.Delay(TimeSpan.FromSeconds(1), TimeProvider.System));
        }

        foreach (var link in new[] { _stageHost, _laserHost })
        {
            if (link is not null)
            {
                await link.DisposeAsync();
            }
        }
    }

    // Each link draws its latencies from its own seeded source, so the stage's traffic does not shift the gate's draws.
    private LinkLatency NewLatency(Jitter processing = default)
    {
        var seed = _random.Next();
        var latency = new LinkLatency(Options.AdapterLatency, processing, new Random(seed));

        // Pieces draw from a stream of their own (derived from the link's), so the latencies are the same with or without them.
        return Options.ReplyPieces.IsNone ? latency : latency.WithPieces(Options.ReplyPieces, new Random(seed ^ 0x50494543));
    }

    private ISerialLink ServeInProcessStage()
    {
        var (host, device) = InMemorySerialLink.CreatePair("simulated stage", TimeProvider);
        ServeStage(device);
        return Loaded(host, 1);
    }

    private ISerialLink ServeInProcessLaser()
    {
        var (host, device) = InMemorySerialLink.CreatePair("simulated laser gate", TimeProvider);
        ServeLaser(device);
        return Loaded(host, 2);
    }

    // The host's end as a loaded computer uses it (stalled writes, late reads), in virtual time; each link its own stream.
    private ISerialLink Loaded(ISerialLink host, int link)
    {
        var lateness = Options.HostLateness;
        if (_virtual is null || (!lateness.Stalls && !lateness.ReadsLate))
        {
            return host;
        }

        _loadedLinks++;
        return new LoadedHostLink(host, TimeProvider, lateness, new Random(unchecked((Options.Seed * 7919) + (link * 104729) + (_loadedLinks * 31)) ^ 0x53544C4C));
    }

    private Task Track(string port, ISerialLink link, Func<Action<string>, Task> serve)
    {
        Raise(port, $"serving {link.Name}");
        var task = _runner.Start(async () =>
        {
            try
            {
                await serve(message => Raise(port, message));
            }
            finally
            {
                await link.DisposeAsync();
            }
        });
        lock (_tasksLock)
        {
            _tasks.RemoveAll(t => t.IsCompleted);
            _tasks.Add(task);
        }

        return task;
    }

    private static long StartPosition(AxisProfile axis, SimulatorOptions options, int index) =>
        options.StartMicrosteps is { } start && index < start.Count ? Math.Clamp(start[index], 0, axis.TravelMicrosteps)
        : options.StartMm is { } mm ? Math.Clamp((long)Math.Round(StageUnits.MmToMicrosteps(mm, axis.MicrostepUm)), 0, axis.TravelMicrosteps) : axis.TravelMicrosteps;

    private void Raise(string port, string message) => EventRaised?.Invoke(this, new SimulatorEvent(TimeProvider.GetUtcNow(), port, message));
}

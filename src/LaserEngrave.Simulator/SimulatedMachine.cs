using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Machine;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Simulator.Burn;
using LaserEngrave.Simulator.Faults;
using LaserEngrave.Simulator.LaserGate;
using LaserEngrave.Simulator.Timing;
using LaserEngrave.Simulator.Zaber;

namespace LaserEngrave.Simulator;

/// <summary>The whole machine in software: the Zaber chain on one link, the laser gate on another, a burn recorder and faults.</summary>
/// <remarks>
/// In-process (<see cref="CreateInProcess"/>) the host talks to <see cref="StageLink"/> and <see cref="LaserLink"/>
/// and must use <see cref="TimeProvider"/> for every wait. Attached (<see cref="Attach"/>) the simulator serves the
/// device ends of real ports or ptys for a host in another process, living in real time: in virtual time the devices'
/// own waiting (motion, bytes on the wire) is fast-forwarded, while what measures the host (the gate's watchdog, the
/// 10 ms gap that drops a partial Zaber frame) runs on the wall clock. Runs until disposed.
/// </remarks>
public sealed class SimulatedMachine : IAsyncDisposable
{
    /// <summary>Port name of the stage in events.</summary>
    public const string StagePort = "stage";

    /// <summary>Port name of the laser gate in events.</summary>
    public const string LaserPort = "laser";

    private readonly CancellationTokenSource _stop = new();
    private readonly SimulationClock _clock;
    private readonly VirtualTimeProvider? _ownedClock;
    private readonly bool _inProcess;
    private ISerialLink? _stageHost;
    private ISerialLink? _laserHost;
    private readonly Lock _tasksLock = new();
    private readonly List<Task> _tasks = [];
    private Task _stageServed = Task.CompletedTask;
    private Task _laserServed = Task.CompletedTask;

    private SimulatedMachine(MachineProfile profile, SimulatorOptions options, bool inProcess)
    {
        ArgumentNullException.ThrowIfNull(profile);
        ArgumentNullException.ThrowIfNull(options);
        profile.Validate();
        Profile = profile;
        Options = options;
        if (options.TimeProvider is { } shared)
        {
            TimeProvider = shared;
        }
        else if (options.RealTime)
        {
            TimeProvider = TimeProvider.System;
        }
        else
        {
            _ownedClock = new VirtualTimeProvider(quietPeriod: options.QuietPeriod, waitForRunnableThreads: inProcess);
            TimeProvider = _ownedClock;
        }

        // In-process the host shares the clock; attached, the host is another process on the wall clock.
        _clock = new SimulationClock(TimeProvider, inProcess ? TimeProvider : System.TimeProvider.System);
        Faults = FaultInjector.Parse(options.FaultSpec);
        Faults.Triggered += (_, rule) => Raise(rule.Target == FaultTarget.Stage ? StagePort : LaserPort, $"fault injected: {rule}");
        var x = new Motion.AxisTrajectory(profile.X.TravelMicrosteps);
        var y = new Motion.AxisTrajectory(profile.Y.TravelMicrosteps);
        Recorder = new BurnRecorder(x, y, profile.X.MicrostepUm, profile.Y.MicrostepUm, options.DwellTolerance, () => _clock.NowSeconds);
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

    /// <summary>The Zaber chain (X, Y).</summary>
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

    /// <summary>A machine on in-memory links, for tests and the app: the host uses <see cref="StageLink"/> and <see cref="LaserLink"/>.</summary>
    public static SimulatedMachine CreateInProcess(MachineProfile profile, SimulatorOptions? options = null)
    {
        return new SimulatedMachine(profile, options ?? new SimulatorOptions(), inProcess: true);
    }

    /// <summary>A machine on in-memory links with the host's stage and gate already on them; the session's <see cref="MachineSession.Owner"/> is the machine, disposed with it.</summary>
    public static MachineSession OpenInProcess(MachineProfile profile, SimulatorOptions? options = null)
    {
        var machine = CreateInProcess(profile, options);
        return MachineSession.OverLinks(machine.StageLink, machine.LaserLink, profile, machine.TimeProvider, "simulator", owner: machine);
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
        _stageServed = Track(StagePort, deviceEnd, (log, starting) => Stage.RunAsync(deviceEnd, log, starting, _stop.Token));
    }

    /// <summary>Serves a new laser gate link; the gate keeps its state.</summary>
    public void ServeLaser(ISerialLink deviceEnd)
    {
        ArgumentNullException.ThrowIfNull(deviceEnd);
        _laserServed = Track(LaserPort, deviceEnd, (log, starting) => Gate.RunAsync(deviceEnd, log, starting, _stop.Token));
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

        await _stageHost!.DisposeAsync().ConfigureAwait(false);
        await _laserHost!.DisposeAsync().ConfigureAwait(false);
        await _stageServed.ConfigureAwait(false);
        await _laserServed.ConfigureAwait(false);
        _stageHost = ServeInProcessStage();
        _laserHost = ServeInProcessLaser();
    }

    /// <summary>Stops serving, closes the links and, in virtual time, stops the clock.</summary>
    public async ValueTask DisposeAsync()
    {
        if (_stop.IsCancellationRequested)
        {
            return;
        }

        await _stop.CancelAsync().ConfigureAwait(false);
        Task[] tasks;
        lock (_tasksLock)
        {
            tasks = [.. _tasks];
        }

        // A blocking stream (a pty file) may not notice the cancellation until its peer goes away: do not wait for ever.
        await Task.WhenAny(Task.WhenAll(tasks), Task.Delay(TimeSpan.FromSeconds(1), TimeProvider.System)).ConfigureAwait(false);
        foreach (var link in new[] { _stageHost, _laserHost })
        {
            if (link is not null)
            {
                await link.DisposeAsync().ConfigureAwait(false);
            }
        }

        _ownedClock?.Dispose();
        _stop.Dispose();
    }

    private ISerialLink ServeInProcessStage()
    {
        var (host, device) = InMemorySerialLink.CreatePair("simulated stage");
        var (wrappedHost, wrappedDevice) = ActivityLink.WrapPair(host, device, _clock);
        ServeStage(wrappedDevice);
        return wrappedHost;
    }

    private ISerialLink ServeInProcessLaser()
    {
        var (host, device) = InMemorySerialLink.CreatePair("simulated laser gate");
        var (wrappedHost, wrappedDevice) = ActivityLink.WrapPair(host, device, _clock);
        ServeLaser(wrappedDevice);
        return wrappedHost;
    }

    private Task Track(string port, ISerialLink link, Func<Action<string>, ClockHold, Task> serve)
    {
        Raise(port, $"serving {link.Name}");

        // Virtual time must not move while the session is still starting (queued, or being compiled): the host may
        // already have written a command and set a timeout, which would otherwise be the only timer to jump to.
        var starting = _clock.Hold();
        var task = Task.Run(async () =>
        {
            try
            {
                await serve(message => Raise(port, message), starting).ConfigureAwait(false);
            }
            finally
            {
                starting.Dispose();
                await link.DisposeAsync().ConfigureAwait(false);
            }
        });
        lock (_tasksLock)
        {
            _tasks.RemoveAll(t => t.IsCompleted);
            _tasks.Add(task);
        }

        return task;
    }

    private void Raise(string port, string message) => EventRaised?.Invoke(this, new SimulatorEvent(TimeProvider.GetUtcNow(), port, message));
}

using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Wire.Scheduling;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Machine view: simulator or real ports, connect, identify, home, and the state of both axes and the gate.</summary>
public sealed partial class MachineViewModel : ObservableObject
{
    private readonly IMachineConnectionFactory _factory;

    /// <param name="activity">The app's one record of what holds the machine; a new one when not shared (tests).</param>
    public MachineViewModel(IMachineConnectionFactory factory, MachineProfile profile, MachineActivity? activity = null)
    {
        ArgumentNullException.ThrowIfNull(factory);
        ArgumentNullException.ThrowIfNull(profile);
        _factory = factory;
        Profile = profile;
        Activity = activity ?? new MachineActivity();
        Activity.PropertyChanged += (_, e) =>
        {
            if (e.PropertyName == nameof(MachineActivity.Current))
            {
                OnPropertyChanged(nameof(IsBusy));
                foreach (var command in new IRelayCommand[] { ConnectCommand, DisconnectCommand, IdentifyCommand, HomeCommand })
                {
                    command.NotifyCanExecuteChanged();
                }
            }
        };
    }

    /// <summary>What holds the machine now; shared by every view-model that drives it.</summary>
    public MachineActivity Activity { get; }

    [ObservableProperty]
    public partial bool UseSimulator { get; set; } = true;

    [ObservableProperty]
    public partial string? StagePort { get; set; }

    [ObservableProperty]
    public partial string? LaserPort { get; set; }

    [ObservableProperty]
    public partial IReadOnlyList<string> Ports { get; private set; } = [];

    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(GateHasNoWatchdog), nameof(NoWatchdogUnaccepted))]
    public partial MachineProfile Profile { get; set; }

    /// <summary>
    /// The person accepts that the profile's laser gate has no watchdog (the Machine panel's checkbox, or the API's start):
    /// every run of the app passes it on, and its log keeps the sentence accepted.
    /// </summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(NoWatchdogUnaccepted))]
    public partial bool AcceptNoWatchdog { get; set; }

    /// <summary>The profile's gate has no watchdog (a frequency-only gate): the panel asks the person to accept it.</summary>
    public bool GateHasNoWatchdog => !Profile.Gate.HasWatchdog;

    /// <summary>Why a run cannot start yet: the gate has no watchdog and nobody accepted it; null otherwise.</summary>
    public string? NoWatchdogUnaccepted => GateHasNoWatchdog && !AcceptNoWatchdog
        ? $"{LaserGateProfile.NoWatchdogSentence}; tick \"I accept\" in the Machine panel to run"
        : null;

    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(ConnectCommand), nameof(DisconnectCommand), nameof(IdentifyCommand), nameof(HomeCommand))]
    public partial IMachineConnection? Connection { get; private set; }

    [ObservableProperty]
    public partial string? Identity { get; private set; }

    [ObservableProperty]
    public partial long? XMicrosteps { get; set; }

    [ObservableProperty]
    public partial long? YMicrosteps { get; set; }

    [ObservableProperty]
    public partial bool? XHomed { get; private set; }

    [ObservableProperty]
    public partial bool? YHomed { get; private set; }

    /// <summary>
    /// The laser as last known, the one source the panel, the page's state and the API read: the gate's own answer when
    /// nothing runs, and during a run the engine's, which knows when a burst is under way (the gate is not asked then).
    /// </summary>
    [ObservableProperty]
    [NotifyPropertyChangedFor(nameof(GateState))]
    public partial LaserGateState? Laser { get; set; }

    /// <summary>The laser's state in words ("off", "firing at 1000 Hz"), from <see cref="Laser"/>.</summary>
    public string? GateState => Laser is { } laser ? Describe(laser) : _laserUnknownWhy;

    private string? _laserUnknownWhy;

    /// <summary>The last failure of a machine command, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; set; }

    /// <summary>Whether any operation holds the machine (then the machine commands are disabled).</summary>
    public bool IsBusy => Activity.IsBusy;

    public bool IsConnected => Connection is not null;

    /// <summary>Whether <see cref="ConnectCommand"/> is offered: nothing holds the machine (the interlock decides first), not connected yet.</summary>
    public bool CanConnect => !Activity.IsBusy && Connection is null;

    /// <summary>Connected and nothing holds the machine (the interlock decides first).</summary>
    public bool CanUseMachine => !Activity.IsBusy && Connection is not null;

    /// <summary>What the last "List ports" found, one line (the port fields offer the ports too, but only once focused).</summary>
    [ObservableProperty]
    public partial string? PortsNote { get; private set; }

    public void RefreshPorts()
    {
        try
        {
            Ports = _factory.ListPorts();
            PortsNote = Ports.Count == 0
                ? "No serial ports found on this computer: is the USB-serial adapter plugged in and its driver installed?"
                : $"{Ports.Count} serial port{(Ports.Count == 1 ? "" : "s")} found: {string.Join(", ", Ports)}";
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or DeviceException)
        {
            PortsNote = null;
            Error = $"cannot list the serial ports: {ex.Message}";
        }
    }

    /// <summary>Opens the machine and reads its state; any failure leaves it disconnected with the reason shown.</summary>
    [RelayCommand(CanExecute = nameof(CanConnect))]
    private Task ConnectAsync() => Guard(MachineOperation.Connecting, async cancellationToken =>
    {
        await CloseAsync();
        var connection = await _factory.ConnectAsync(new MachineChoice(UseSimulator, StagePort, LaserPort), Profile, cancellationToken);
        Connection = connection;
        OnPropertyChanged(nameof(IsConnected));
        try
        {
            await TaskRunner.Run(connection.TimeProvider, () => ReadStateAsync(connection, cancellationToken));
        }
        catch
        {
            // A machine that does not answer is closed again, so the next connect starts clean.
            await CloseAsync();
            throw;
        }
    });

    [RelayCommand(CanExecute = nameof(CanUseMachine))]
    private Task DisconnectAsync() => Guard(MachineOperation.Disconnecting, _ => CloseAsync());

    [RelayCommand(CanExecute = nameof(CanUseMachine))]
    private Task IdentifyAsync() =>
        Guard(MachineOperation.Identifying, cancellationToken => ReadStateAsync(RequireConnection(), cancellationToken));

    /// <summary>Homes both axes together, the laser switched off first.</summary>
    [RelayCommand(CanExecute = nameof(CanUseMachine))]
    private Task HomeAsync() => Guard(MachineOperation.Homing, async cancellationToken =>
    {
        var connection = RequireConnection();
        await connection.Gate.OffAsync(cancellationToken);
        await FollowAsync(Task.WhenAll(connection.Stage.X.HomeAsync(cancellationToken), connection.Stage.Y.HomeAsync(cancellationToken)), cancellationToken);
        await ReadStateAsync(connection, cancellationToken);
    });

    /// <summary>How often the positions are read while the stage moves (a test move, a jog, homing).</summary>
    public static TimeSpan FollowInterval { get; } = TimeSpan.FromMilliseconds(200);

    /// <summary>
    /// Waits for <paramref name="motion"/>, reading both positions every <see cref="FollowInterval"/> of the machine's
    /// clock meanwhile, so the position and the laser's cross move at the stage's own pace instead of jumping at the end.
    /// </summary>
    /// <remarks>A position the stage does not give (a fault) only ends the following: the motion's own end says what went wrong.</remarks>
    internal async Task FollowAsync(Task motion, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(motion);
        if (Connection is { } connection)
        {
            using var stop = CancellationTokenSource.CreateLinkedTokenSource(cancellationToken);
            try
            {
                while (!motion.IsCompleted)
                {
                    var tick = Task.Delay(FollowInterval, connection.TimeProvider, stop.Token);
                    if (await Task.WhenAny(motion, tick) == motion || tick.IsCanceled)
                    {
                        // Ended, or stopped: the motion's end is awaited below.
                        break;
                    }

                    XMicrosteps = await connection.Stage.X.GetPositionAsync(stop.Token);
                    YMicrosteps = await connection.Stage.Y.GetPositionAsync(stop.Token);
                }
            }
            catch (Exception ex) when (ex is DeviceException or OperationCanceledException or TimeoutException or IOException or InvalidOperationException or ObjectDisposedException)
            {
                // The motion decides the outcome below.
            }
            finally
            {
                // Cancel, not CancelAsync: CancelAsync runs the pending tick's callback on the thread pool, and the
                // simulation's loop (unpaced virtual time), seeing no work of its own while waiting for it, reported a deadlock.
                stop.Cancel();
            }
        }

        await motion;
    }

    /// <summary>
    /// A run or sweep got past its preflight, which homes every axis that is not homed (docs/execution.md): the panel says
    /// so at once, not only once the run has ended.
    /// </summary>
    internal void PreflightHomed()
    {
        XHomed = true;
        YHomed = true;
    }

    /// <summary>
    /// The machine did not answer when read after a run (a stage gone silent): whether the axes are homed is no longer
    /// known, so the panel says "?" rather than the homed it read before; the positions stay the run's last known.
    /// </summary>
    internal void StateNotKnown()
    {
        XHomed = YHomed = null;
    }

    /// <summary>Closes the connection whatever holds the machine: for the app's exit, after the run was aborted.</summary>
    internal async Task CloseAsync()
    {
        var connection = Connection;
        Connection = null;
        OnPropertyChanged(nameof(IsConnected));
        Identity = null;
        XMicrosteps = YMicrosteps = null;
        XHomed = YHomed = null;
        _laserUnknownWhy = null;
        Laser = null;
        if (connection is not null)
        {
            await connection.DisposeAsync();
        }
    }

    /// <summary>Reads both positions and the gate's state again.</summary>
    public Task ReadPositionsAsync(CancellationToken cancellationToken)
    {
        var connection = RequireConnection();
        return TaskRunner.Run(connection.TimeProvider, async () =>
        {
            XMicrosteps = await connection.Stage.X.GetPositionAsync(cancellationToken);
            YMicrosteps = await connection.Stage.Y.GetPositionAsync(cancellationToken);
        });
    }

    /// <summary>Reads homed flags, the gate and both positions again (after a run, which homes in its preflight).</summary>
    public Task RefreshStateAsync(CancellationToken cancellationToken)
    {
        var connection = RequireConnection();
        return TaskRunner.Run(connection.TimeProvider, () => ReadStateAsync(connection, cancellationToken));
    }

    internal IMachineConnection RequireConnection() => Connection ?? throw new DeviceException("not connected: connect to the simulator or the machine first");

    /// <summary>
    /// Runs a machine command holding the machine for <paramref name="operation"/>, showing its failure as <see cref="Error"/>;
    /// refused with one line when another operation holds the machine; never throws what the user caused.
    /// </summary>
    /// <returns>False when refused because the machine is busy.</returns>
    internal async Task<bool> Guard(MachineOperation operation, Func<CancellationToken, Task> action)
    {
        if (!Activity.TryBegin(operation, out var lease, out var refusal))
        {
            Error = refusal;
            return false;
        }

        using (lease)
        {
            Error = null;
            try
            {
                // Where the machine's clock says: on the simulation's loop in virtual time.
                await TaskRunner.Run(Connection?.TimeProvider ?? TimeProvider.System, () => action(lease.CancellationToken));
            }
            catch (OperationCanceledException)
            {
                Error = "cancelled";
            }
            catch (Exception ex) when (ex is DeviceException or IOException or UnauthorizedAccessException or InvalidOperationException or ArgumentException or TimeoutException)
            {
                Error = ex.Message;
            }
        }

        return true;
    }

    private async Task ReadStateAsync(IMachineConnection connection, CancellationToken cancellationToken)
    {
        var x = await connection.Stage.X.IdentifyAsync(cancellationToken);
        var y = await connection.Stage.Y.IdentifyAsync(cancellationToken);
        var gate = await connection.Gate.IdentifyAsync(cancellationToken);
        Identity = $"X: device {x.DeviceNumber}, id {x.DeviceId}, firmware {x.FirmwareText}; Y: device {y.DeviceNumber}, id {y.DeviceId}, firmware {y.FirmwareText}; gate: {gate}";
        XHomed = x.IsHomed;
        YHomed = y.IsHomed;
        await ReadLaserAsync(connection.Gate, cancellationToken);
        await ReadPositionsAsync(cancellationToken);
    }

    /// <summary>
    /// Asks the gate its state as the laser's state; a frequency-only gate reports nothing, so the laser is then unknown
    /// until a run reports it, and the panel says why.
    /// </summary>
    internal async Task ReadLaserAsync(ILaserGate gate, CancellationToken cancellationToken)
    {
        if (Profile.Gate.CountsBursts)
        {
            _laserUnknownWhy = null;
            Laser = await gate.GetStateAsync(cancellationToken);
        }
        else
        {
            _laserUnknownWhy = FrequencyOnlyGateNote;
            Laser = null;
            OnPropertyChanged(nameof(GateState));
        }
    }

    /// <summary>What the panel says of the laser on a gate that reports no state.</summary>
    internal const string FrequencyOnlyGateNote = "a frequency-only gate: it reports no state and has no watchdog";

    /// <summary>
    /// A run's report of the laser (<see cref="LaserEngrave.Devices.Execution.RunProgress.LaserOn"/>) as the laser's state:
    /// firing at the run's frequency or off, the watchdog as the gate last said.
    /// </summary>
    internal void RunLaser(bool on, int frequencyHz)
    {
        var last = Laser;
        var now = new LaserGateState(on ? frequencyHz : 0, on, last?.WatchdogMs ?? 0, last?.WatchdogTripped == true && !on);
        if (now != last)
        {
            Laser = now;
        }
    }

    internal static string Describe(LaserGateState state) =>
        (state.Firing ? $"firing at {state.FrequencyHz} Hz" : "off") + (state.WatchdogTripped ? ", watchdog tripped" : string.Empty);
}

using CommunityToolkit.Mvvm.ComponentModel;
using CommunityToolkit.Mvvm.Input;
using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.ViewModels;

/// <summary>The Machine view: simulator or real ports, connect, identify, home, and the state of both axes and the gate.</summary>
public sealed partial class MachineViewModel : ObservableObject
{
    private readonly IMachineConnectionFactory _factory;

    public MachineViewModel(IMachineConnectionFactory factory, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(factory);
        ArgumentNullException.ThrowIfNull(profile);
        _factory = factory;
        Profile = profile;
    }

    [ObservableProperty]
    public partial bool UseSimulator { get; set; } = true;

    [ObservableProperty]
    public partial string? StagePort { get; set; }

    [ObservableProperty]
    public partial string? LaserPort { get; set; }

    [ObservableProperty]
    public partial IReadOnlyList<string> Ports { get; private set; } = [];

    [ObservableProperty]
    public partial MachineProfile Profile { get; set; }

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

    [ObservableProperty]
    public partial string? GateState { get; set; }

    /// <summary>The last failure of a machine command, one line.</summary>
    [ObservableProperty]
    public partial string? Error { get; set; }

    [ObservableProperty]
    [NotifyCanExecuteChangedFor(nameof(ConnectCommand), nameof(IdentifyCommand), nameof(HomeCommand))]
    public partial bool IsBusy { get; private set; }

    public bool IsConnected => Connection is not null;

    public bool CanConnect => Connection is null && !IsBusy;

    /// <summary>Connected and no machine command under way.</summary>
    public bool CanUseMachine => Connection is not null && !IsBusy;

    public void RefreshPorts()
    {
        try
        {
            Ports = _factory.ListPorts();
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or DeviceException)
        {
            Error = $"cannot list the serial ports: {ex.Message}";
        }
    }

    /// <summary>Opens the machine and reads its state; any failure leaves it disconnected with the reason shown.</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanConnect))]
    private async Task ConnectAsync(CancellationToken cancellationToken)
    {
        await DisconnectAsync().ConfigureAwait(false);
        await Guard(async () =>
        {
            var connection = await _factory.ConnectAsync(new MachineChoice(UseSimulator, StagePort, LaserPort), Profile, cancellationToken).ConfigureAwait(false);
            Connection = connection;
            OnPropertyChanged(nameof(IsConnected));
            try
            {
                await ReadStateAsync(connection, cancellationToken).ConfigureAwait(false);
            }
            catch
            {
                // A machine that does not answer is closed again, so the next connect starts clean.
                await DisconnectAsync().ConfigureAwait(false);
                throw;
            }
        }).ConfigureAwait(false);
    }

    [RelayCommand(CanExecute = nameof(IsConnected))]
    private async Task DisconnectAsync()
    {
        var connection = Connection;
        Connection = null;
        OnPropertyChanged(nameof(IsConnected));
        Identity = null;
        XMicrosteps = YMicrosteps = null;
        XHomed = YHomed = null;
        GateState = null;
        if (connection is not null)
        {
            await connection.DisposeAsync().ConfigureAwait(false);
        }
    }

    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanUseMachine))]
    private Task IdentifyAsync(CancellationToken cancellationToken) =>
        Guard(() => ReadStateAsync(RequireConnection(), cancellationToken));

    /// <summary>Homes both axes together, the laser switched off first.</summary>
    [RelayCommand(IncludeCancelCommand = true, CanExecute = nameof(CanUseMachine))]
    private Task HomeAsync(CancellationToken cancellationToken) => Guard(async () =>
    {
        var connection = RequireConnection();
        await connection.Gate.OffAsync(cancellationToken).ConfigureAwait(false);
        await Task.WhenAll(connection.Stage.X.HomeAsync(cancellationToken), connection.Stage.Y.HomeAsync(cancellationToken)).ConfigureAwait(false);
        await ReadStateAsync(connection, cancellationToken).ConfigureAwait(false);
    });

    /// <summary>Reads both positions and the gate's state again.</summary>
    public async Task ReadPositionsAsync(CancellationToken cancellationToken)
    {
        var connection = RequireConnection();
        XMicrosteps = await connection.Stage.X.GetPositionAsync(cancellationToken).ConfigureAwait(false);
        YMicrosteps = await connection.Stage.Y.GetPositionAsync(cancellationToken).ConfigureAwait(false);
    }

    /// <summary>Reads homed flags, the gate and both positions again (after a run, which homes in its preflight).</summary>
    public Task RefreshStateAsync(CancellationToken cancellationToken) => ReadStateAsync(RequireConnection(), cancellationToken);

    internal IMachineConnection RequireConnection() => Connection ?? throw new DeviceException("not connected: connect to the simulator or the machine first");

    /// <summary>Runs a machine command, showing its failure as <see cref="Error"/>; never throws what the user caused.</summary>
    internal async Task Guard(Func<Task> action)
    {
        IsBusy = true;
        Error = null;
        try
        {
            await action().ConfigureAwait(false);
        }
        catch (OperationCanceledException)
        {
            Error = "cancelled";
        }
        catch (Exception ex) when (ex is DeviceException or IOException or UnauthorizedAccessException or InvalidOperationException or ArgumentException or TimeoutException)
        {
            Error = ex.Message;
        }
        finally
        {
            IsBusy = false;
        }
    }

    private async Task ReadStateAsync(IMachineConnection connection, CancellationToken cancellationToken)
    {
        var x = await connection.Stage.X.IdentifyAsync(cancellationToken).ConfigureAwait(false);
        var y = await connection.Stage.Y.IdentifyAsync(cancellationToken).ConfigureAwait(false);
        var gate = await connection.Gate.IdentifyAsync(cancellationToken).ConfigureAwait(false);
        var state = await connection.Gate.GetStateAsync(cancellationToken).ConfigureAwait(false);
        Identity = $"X: device {x.DeviceNumber}, id {x.DeviceId}, firmware {x.FirmwareText}; Y: device {y.DeviceNumber}, id {y.DeviceId}, firmware {y.FirmwareText}; gate: {gate}";
        XHomed = x.IsHomed;
        YHomed = y.IsHomed;
        GateState = Describe(state);
        await ReadPositionsAsync(cancellationToken).ConfigureAwait(false);
    }

    internal static string Describe(LaserGateState state) =>
        (state.Firing ? $"firing at {state.FrequencyHz} Hz" : "off") + (state.WatchdogTripped ? ", watchdog tripped" : string.Empty);
}

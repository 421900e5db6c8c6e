using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.LaserGate;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Zaber;
using LaserEngrave.Wire.Scheduling;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.Machine;

/// <summary>An open machine: the Zaber chain and the laser gate, the clock they wait on, and what owns their links.</summary>
/// <remarks>Disposing closes the gate, then the stage, then the owner (the simulator behind in-process links).</remarks>
public sealed class MachineSession : IAsyncDisposable
{
    private MachineSession(ZaberChain stage, PicLaserGate gate, TimeProvider timeProvider, string stagePort, string laserPort, IAsyncDisposable? owner)
    {
        Stage = stage;
        Gate = gate;
        TimeProvider = timeProvider;
        StagePort = stagePort;
        LaserPort = laserPort;
        Owner = owner;
    }

    public ZaberChain Stage { get; }

    public PicLaserGate Gate { get; }

    /// <summary>The clock every wait uses: the system's on real ports, the simulator's (possibly virtual) in-process.</summary>
    public TimeProvider TimeProvider { get; }

    /// <summary>The stage's port, as logs and messages name it.</summary>
    public string StagePort { get; }

    /// <summary>The laser gate's port, as logs and messages name it.</summary>
    public string LaserPort { get; }

    private WireRecorder? _recorder;

    /// <summary>What the links belong to and is closed last (the in-process simulator); null on real ports.</summary>
    public IAsyncDisposable? Owner { get; }

    /// <summary>Opens two serial ports at the profile's baud rates; the stage's port is closed again if the gate's cannot be opened.</summary>
    /// <param name="stagePort">The stage's port.</param>
    /// <param name="laserPort">The laser gate's port.</param>
    /// <param name="profile">The machine.</param>
    /// <param name="recorder">The flight recorder both links write through; null records nothing.</param>
    public static MachineSession OpenPorts(string stagePort, string laserPort, MachineProfile profile, WireRecorder? recorder = null)
    {
        ArgumentNullException.ThrowIfNull(profile);
        if (recorder is not null)
        {
            return OpenRecorded(stagePort, laserPort, profile, recorder);
        }

        var stage = ZaberChain.Open(stagePort, profile);
        try
        {
            return new MachineSession(stage, PicLaserGate.Open(laserPort, profile.Gate), TimeProvider.System, stagePort, laserPort, null);
        }
        catch
        {
            stage.DisposeAsync().AsTask().GetAwaiter().GetResult();
            throw;
        }
    }

    /// <summary>The stage's and the gate's serial ports, each at the profile's baud rate; the stage's is closed again if the gate's cannot open.</summary>
    public static (ISerialLink Stage, ISerialLink Laser) OpenLinks(string stagePort, string laserPort, MachineProfile profile)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var stageLink = SerialPortLink.Open(new SerialPortSettings(stagePort) { BaudRate = profile.StageBaudRate });
        try
        {
            return (stageLink, SerialPortLink.Open(new SerialPortSettings(laserPort) { BaudRate = profile.Gate.BaudRate }));
        }
        catch
        {
            stageLink.DisposeAsync().AsTask().GetAwaiter().GetResult();
            throw;
        }
    }

    private static MachineSession OpenRecorded(string stagePort, string laserPort, MachineProfile profile, WireRecorder recorder)
    {
        var (stageLink, laserLink) = OpenLinks(stagePort, laserPort, profile);
        var stage = new ZaberChain(new ZaberConnection(recorder.Wrap(stageLink, stage: true), TimeProvider.System), profile);
        var gate = new PicLaserGate(recorder.Wrap(laserLink, stage: false), profile.Gate, TimeProvider.System);
        return new MachineSession(stage, gate, TimeProvider.System, stagePort, laserPort, null);
    }

    /// <summary>The machine on two links already open (in-process links to the simulator), named <paramref name="name"/>.</summary>
    /// <param name="recorder">A flight recorder both links write through (the twin's wire traffic, to compare builds), finished when the session closes; null records nothing.</param>
    public static MachineSession OverLinks(ISerialLink stageLink, ISerialLink laserLink, MachineProfile profile, TimeProvider timeProvider, string name, IAsyncDisposable? owner, WireRecorder? recorder = null)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var stage = new ZaberChain(new ZaberConnection(recorder?.Wrap(stageLink, stage: true) ?? stageLink, timeProvider), profile);
        var gate = new PicLaserGate(recorder?.Wrap(laserLink, stage: false) ?? laserLink, profile.Gate, timeProvider);
        return new MachineSession(stage, gate, timeProvider, name, name, owner) { _recorder = recorder };
    }

    /// <summary>Runs an operation on the machine (a run, a test move) where its clock says: on the simulation's loop in virtual time, else as it is.</summary>
    public Task<T> RunAsync<T>(Func<Task<T>> operation) => TaskRunner.For(TimeProvider).Run(operation);

    /// <summary>Runs an operation that returns nothing; see <see cref="RunAsync{T}"/>.</summary>
    public Task RunAsync(Func<Task> operation) => TaskRunner.Run(TimeProvider, operation);

    public async ValueTask DisposeAsync()
    {
        // Through the runner: in virtual time, closing may wait on the clock (a resynchronisation's quiet period).
        await RunAsync(async () =>
        {
            await Gate.DisposeAsync();
            await Stage.DisposeAsync();
        });
        _recorder?.Finish();
        if (Owner is not null)
        {
            await Owner.DisposeAsync();
        }
    }
}

using System.Collections.Concurrent;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Wraps a stage and a gate and logs every command, in the order sent, to check what came before what.</summary>
internal sealed class RecordingDevices
{
    public RecordingDevices(IStage stage, ILaserGate gate)
    {
        Stage = new RecordingStage(new RecordingAxis(stage.X, "X", this), new RecordingAxis(stage.Y, "Y", this));
        Gate = new RecordingGate(gate, this);
    }

    public ConcurrentQueue<string> Log { get; } = new();

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    public void Add(string entry) => Log.Enqueue(entry);

    private sealed record RecordingStage(IStageAxis X, IStageAxis Y) : IStage;

    private sealed class RecordingAxis(IStageAxis inner, string name, RecordingDevices log) : IStageAxis
    {
        public byte DeviceNumber => inner.DeviceNumber;

        public Task<long> HomeAsync(CancellationToken cancellationToken) => Logged("home", () => inner.HomeAsync(cancellationToken));

        public Task<long> MoveAbsoluteAsync(long position, CancellationToken cancellationToken) => Logged($"move {position}", () => inner.MoveAbsoluteAsync(position, cancellationToken));

        public Task<long> MoveAbsoluteAfterAsync(long position, CancellationToken cancellationToken) => Logged($"move {position}", () => inner.MoveAbsoluteAfterAsync(position, cancellationToken));

        public Task<long> MoveRelativeAsync(long distance, CancellationToken cancellationToken) => Logged($"move by {distance}", () => inner.MoveRelativeAsync(distance, cancellationToken));

        public Task<long> StopAsync(CancellationToken cancellationToken) => Logged("stop", () => inner.StopAsync(cancellationToken));

        public Task<long> GetPositionAsync(CancellationToken cancellationToken) => inner.GetPositionAsync(cancellationToken);

        public Task SetTargetSpeedAsync(int speedData, CancellationToken cancellationToken) => Logged($"speed {speedData}", () => inner.SetTargetSpeedAsync(speedData, cancellationToken));

        public Task SetAccelerationAsync(int accelerationData, CancellationToken cancellationToken) => Logged($"acceleration {accelerationData}", () => inner.SetAccelerationAsync(accelerationData, cancellationToken));

        public Task<AxisIdentity> IdentifyAsync(CancellationToken cancellationToken) => inner.IdentifyAsync(cancellationToken);

        private T Logged<T>(string what, Func<T> call)
        {
            log.Add($"{name} {what}");
            return call();
        }
    }

    private sealed class RecordingGate(ILaserGate inner, RecordingDevices log) : ILaserGate
    {
        public Task<string> IdentifyAsync(CancellationToken cancellationToken) => inner.IdentifyAsync(cancellationToken);

        public Task SetFrequencyAsync(int frequencyHz, CancellationToken cancellationToken)
        {
            log.Add($"laser {frequencyHz}");
            return inner.SetFrequencyAsync(frequencyHz, cancellationToken);
        }

        public Task OffAsync(CancellationToken cancellationToken)
        {
            log.Add("laser off");
            return inner.OffAsync(cancellationToken);
        }

        public Task<LaserGateState> GetStateAsync(CancellationToken cancellationToken) => inner.GetStateAsync(cancellationToken);

        public Task KeepAliveAsync(CancellationToken cancellationToken) => inner.KeepAliveAsync(cancellationToken);

        public Task SetWatchdogAsync(int milliseconds, CancellationToken cancellationToken) => inner.SetWatchdogAsync(milliseconds, cancellationToken);

        public Task BurstAsync(int pulses, int frequencyHz, CancellationToken cancellationToken)
        {
            log.Add($"burst {pulses} {frequencyHz}");
            return inner.BurstAsync(pulses, frequencyHz, cancellationToken);
        }

        public Task EmergencyAsync(EmergencyCommand command, CancellationToken cancellationToken)
        {
            log.Add(command == EmergencyCommand.Off ? "laser off" : $"laser emergency {command}");
            return inner.EmergencyAsync(command, cancellationToken);
        }

        public ValueTask CloseAsync() => inner.CloseAsync();
    }
}

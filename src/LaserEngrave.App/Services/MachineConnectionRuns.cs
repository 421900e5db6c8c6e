using LaserEngrave.Devices.Execution;

namespace LaserEngrave.App.Services;

/// <summary>An open machine as a run's session engraves on it.</summary>
public static class MachineConnectionRuns
{
    /// <summary>The stage, the gate and their clock, named in the log by the connection's description; the twin's burn check on the simulator.</summary>
    public static EngraveMachine Engraving(this IMachineConnection connection)
    {
        ArgumentNullException.ThrowIfNull(connection);
        return new EngraveMachine(connection.Stage, connection.Gate, connection.TimeProvider, connection.Description, connection.Description)
        {
            Simulated = connection.IsSimulated,
            Inspector = connection.IsSimulated ? connection.Inspector : null,
        };
    }
}

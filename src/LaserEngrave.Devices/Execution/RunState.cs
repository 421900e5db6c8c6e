namespace LaserEngrave.Devices.Execution;

/// <summary>Where a run is: the state machine of <see cref="RunExecutor"/>; <see cref="RunStateMachine"/> holds its legal transitions.</summary>
public enum RunState
{
    /// <summary>Not started.</summary>
    Idle,

    /// <summary>Checking the machine and the job before anything moves under the laser.</summary>
    Preflight,

    /// <summary>Executing the plan.</summary>
    Running,

    /// <summary>Pause asked: finishing the current burn run, then the laser goes off.</summary>
    Pausing,

    /// <summary>Stopped between runs with the laser off; <see cref="RunExecutor.Resume"/> continues.</summary>
    Paused,

    /// <summary>Abort asked: laser off, then both axes stopped.</summary>
    Aborting,

    /// <summary>Ended with every move done.</summary>
    Completed,

    /// <summary>Ended by an abort: the laser off, then both axes stopped; the result has a stop point to resume from.</summary>
    Aborted,

    /// <summary>Ended by a fault or a preflight refusal.</summary>
    Failed,
}

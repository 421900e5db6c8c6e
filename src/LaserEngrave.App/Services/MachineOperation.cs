namespace LaserEngrave.App.Services;

/// <summary>An operation that holds the machine, with the line that tells the user about it.</summary>
/// <param name="Kind">What sort of operation.</param>
/// <param name="Summary">What is running, e.g. "a run is under way".</param>
/// <param name="Doing">What the machine is doing, as the run bar says it while it lasts, e.g. "Tracing the job's frame, laser off…".</param>
public sealed record MachineOperation(MachineOperationKind Kind, string Summary, string Doing)
{
    public static MachineOperation Run { get; } = new(MachineOperationKind.Run, "a run is under way", "Running the job…");

    /// <summary>A parameter sweep: a run of many cells.</summary>
    public static MachineOperation Sweep { get; } = new(MachineOperationKind.Run, "a sweep is under way", "Running the sweep…");

    public static MachineOperation Homing { get; } = new(MachineOperationKind.Homing, "homing is under way", "Homing both axes, laser off…");

    public static MachineOperation Jog { get; } = new(MachineOperationKind.Jog, "a jog is under way", "Jogging, laser off…");

    public static MachineOperation Connecting { get; } = new(MachineOperationKind.Connection, "connecting to the machine is under way", "Connecting…");

    public static MachineOperation Disconnecting { get; } = new(MachineOperationKind.Connection, "disconnecting the machine is under way", "Disconnecting…");

    public static MachineOperation Identifying { get; } = new(MachineOperationKind.Connection, "reading the machine's identity is under way", "Reading the machine's identity…");

    /// <summary>A test move, e.g. "go to", "frame", "test fire"; <paramref name="doing"/> says it while it lasts.</summary>
    public static MachineOperation TestMove(string what, string? doing = null) =>
        new(MachineOperationKind.TestMove, $"a test move ({what}) is under way", doing ?? $"Test move ({what}), laser off…");

    /// <summary>Whether the job must stay as it is meanwhile (it is burned, traced or the stage is moving for it).</summary>
    public bool LocksJob => Kind is MachineOperationKind.Run or MachineOperationKind.Homing or MachineOperationKind.TestMove or MachineOperationKind.Jog;

    /// <summary>What the user can do about it.</summary>
    public string Hint => Kind switch
    {
        MachineOperationKind.Run => "wait for it to end, or pause or abort it first",
        MachineOperationKind.Connection => "wait for it to end",
        _ => "wait for it to end or stop it first",
    };
}

/// <summary>The sorts of operation that hold the machine.</summary>
public enum MachineOperationKind
{
    /// <summary>An engraving run (preflight, passes, continue).</summary>
    Run,

    /// <summary>Both axes homing.</summary>
    Homing,

    /// <summary>A go-to, origin, frame or test fire.</summary>
    TestMove,

    /// <summary>Jog presses being carried out; more presses add to the target.</summary>
    Jog,

    /// <summary>Connecting, identifying or disconnecting.</summary>
    Connection,
}

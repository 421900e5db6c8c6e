namespace LaserEngrave.Core.Logging;

/// <summary>How the laser was confirmed off after a fault or an abort (docs/execution.md, "When the gate refuses OFF").</summary>
public enum LaserOffPath
{
    /// <summary>The gate acknowledged the OFF sent on the fault or the abort: the usual way.</summary>
    Off,

    /// <summary>A switch-off was refused or not answered in time; the gate acknowledged OFF (late, or sent again with every other path).</summary>
    OffAgain,

    /// <summary>A switch-off was refused or went unanswered, and OFF again too; the gate acknowledged FREQ 0.</summary>
    FrequencyZero,

    /// <summary>No path confirmed it: the gate's port was closed so that its watchdog switches the laser off; a person must check the laser.</summary>
    None,
}

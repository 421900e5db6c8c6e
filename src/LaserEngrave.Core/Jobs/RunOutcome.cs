namespace LaserEngrave.Core.Jobs;

/// <summary>How a run ended.</summary>
public enum RunOutcome
{
    /// <summary>Every run of the plan was burned.</summary>
    Completed,

    /// <summary>The operator stopped it (Ctrl+C, the abort button): laser off, stage stopped.</summary>
    Aborted,

    /// <summary>A device fault stopped it: laser off, stage stopped, the place recorded in the fault.</summary>
    Failed,

    /// <summary>The preflight checks refused to start: nothing moved, the laser never fired.</summary>
    Refused,
}

namespace LaserEngrave.App.Services;

/// <summary>Where a run is: moves and rows done, the pass, and the stage's last commanded position.</summary>
/// <param name="MovesDone">Moves completed in this pass.</param>
/// <param name="MovesTotal">Moves in one pass.</param>
/// <param name="RowsDone">Plan rows completed in this pass.</param>
/// <param name="RowsTotal">Plan rows in one pass.</param>
/// <param name="Pass">The pass under way, from 1.</param>
/// <param name="XMicrosteps">Stage X at the end of the last completed move.</param>
/// <param name="YMicrosteps">Stage Y at the end of the last completed move.</param>
/// <param name="LaserOn">Whether the gate is firing.</param>
/// <param name="Phase">What the executor is doing, e.g. "preflight" (checking and homing before the plan) or "running".</param>
/// <param name="PassRemainingSeconds">The executor's estimate of the time left in this pass (the plan's estimate scaled by the pace so far), s; null when unknown.</param>
public sealed record RunProgress(
    long MovesDone,
    long MovesTotal,
    int RowsDone,
    int RowsTotal,
    int Pass,
    long XMicrosteps,
    long YMicrosteps,
    bool LaserOn,
    string Phase = "running",
    double? PassRemainingSeconds = null);

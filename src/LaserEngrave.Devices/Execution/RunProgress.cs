namespace LaserEngrave.Devices.Execution;

/// <summary>A snapshot of a run, raised after every move (no throttling: the front end throttles).</summary>
/// <param name="State">The run's state.</param>
/// <param name="RowsDone">Visited rows finished, over the whole plan (a resumed run counts the rows done before).</param>
/// <param name="RowsTotal">Visited rows of the plan.</param>
/// <param name="RunsDone">Burn runs finished, over the whole plan.</param>
/// <param name="RunsTotal">Burn runs of the plan.</param>
/// <param name="Percent">Share of the plan's estimated time done, 0..100.</param>
/// <param name="Elapsed">Time since the run started, on the run's clock.</param>
/// <param name="Remaining">Estimated time left: the estimate of the moves left times the observed ratio of actual to estimated time.</param>
/// <param name="XMicrosteps">Last known X.</param>
/// <param name="YMicrosteps">Last known Y.</param>
/// <param name="LaserOn">Whether the laser is on.</param>
public sealed record RunProgress(
    RunState State,
    int RowsDone,
    int RowsTotal,
    long RunsDone,
    long RunsTotal,
    double Percent,
    TimeSpan Elapsed,
    TimeSpan Remaining,
    long XMicrosteps,
    long YMicrosteps,
    bool LaserOn);

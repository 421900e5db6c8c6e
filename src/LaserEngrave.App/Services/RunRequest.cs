using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.Services;

/// <summary>What a run needs: the planned job, the machine and its clock, how many passes, and the pause control.</summary>
public sealed record RunRequest(PreparedJob Job, IStage Stage, ILaserGate Gate, int Passes, RunPauseGate Pause)
{
    /// <summary>The clock every wait of the run uses (the simulator's, in virtual time, in tests).</summary>
    public TimeProvider TimeProvider { get; init; } = TimeProvider.System;

    /// <summary>Where a stopped run left off: only the rest of that pass is run, from the first burn run not completed.</summary>
    public RunStopPoint? ResumeFrom { get; init; }
}

using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.App.Services;

/// <summary>What a run needs: the planned job, the machine, how many passes, and the pause control.</summary>
public sealed record RunRequest(PreparedJob Job, IStage Stage, ILaserGate Gate, int Passes, RunPauseGate Pause);

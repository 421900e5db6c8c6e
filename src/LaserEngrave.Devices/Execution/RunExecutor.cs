using LaserEngrave.Core.Jobs;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>Executes a <see cref="PreparedJob"/>'s plan on a stage and a laser gate, safely, waiting only on a <see cref="TimeProvider"/>.</summary>
/// <remarks>
/// One executor runs one job once (<see cref="RunAsync"/>); to resume after a fault make a new executor with
/// <see cref="RunOptions.ResumeFrom"/>. Events are raised on the run's thread: handlers must be quick and must not block.
/// <see cref="Pause"/>, <see cref="Resume"/> and <see cref="Abort"/> may be called from any thread at any time.
/// </remarks>
public sealed class RunExecutor
{
    public RunExecutor(IStage stage, ILaserGate gate, PreparedJob job, TimeProvider? timeProvider = null, RunOptions? options = null)
    {
        ArgumentNullException.ThrowIfNull(stage);
        ArgumentNullException.ThrowIfNull(gate);
        ArgumentNullException.ThrowIfNull(job);
        Stage = stage;
        Gate = gate;
        Job = job;
        TimeProvider = timeProvider ?? TimeProvider.System;
        Options = options ?? RunOptions.Default;
    }

    /// <summary>Raised on every state change.</summary>
    public event EventHandler<RunStateChangedEventArgs>? StateChanged;

    /// <summary>Raised after every move and on every state change.</summary>
    public event EventHandler<RunProgress>? ProgressChanged;

    /// <summary>Raised after every move of the plan, with the move.</summary>
    public event EventHandler<MoveCompletedEventArgs>? MoveCompleted;

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    public PreparedJob Job { get; }

    public TimeProvider TimeProvider { get; }

    public RunOptions Options { get; }

    public RunState State => throw new NotImplementedException();

    /// <summary>The latest progress snapshot.</summary>
    public RunProgress Progress => throw new NotImplementedException();

    /// <summary>Preflight, then the plan; returns how it ended (completed, aborted or failed: faults do not throw).</summary>
    /// <param name="cancellationToken">Cancelling it aborts the run (laser off, then the stage stopped), as <see cref="Abort"/>.</param>
    /// <exception cref="PreflightException">Preflight refused to start; nothing moved under the laser.</exception>
    public Task<RunResult> RunAsync(CancellationToken cancellationToken) => throw new NotImplementedException();

    /// <summary>Stops after the current burn run with the laser off (state Pausing, then Paused).</summary>
    public void Pause() => throw new NotImplementedException();

    /// <summary>Continues a paused (or pausing) run.</summary>
    public void Resume() => throw new NotImplementedException();

    /// <summary>Switches the laser off, then stops both axes; wins over everything else, from any thread, at any time.</summary>
    public void Abort() => throw new NotImplementedException();

    private void Raise(RunStateChangedEventArgs state, RunProgress progress, MoveCompletedEventArgs move)
    {
        StateChanged?.Invoke(this, state);
        ProgressChanged?.Invoke(this, progress);
        MoveCompleted?.Invoke(this, move);
    }
}

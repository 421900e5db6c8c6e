using LaserEngrave.Core.Logging;

namespace LaserEngrave.Devices.Execution;

/// <summary>How an <see cref="EngraveSession"/> ended: the log's record (written or not), the run's result or error.</summary>
/// <param name="Record">The complete record: outcome, times and counts over the passes, passes done, and the simulator's burn check.</param>
/// <param name="Run">The passes' result (times, estimate and laser-on added up, counts the last pass's); null when the run ended without one.</param>
/// <param name="Error">What ended the run without a result (a preflight refusal, a lost port); the caller reports it.</param>
/// <param name="Files">Where the log went; null when it could not be written or no log was asked for.</param>
/// <param name="LogError">Why the log could not be written; null when it was.</param>
public sealed record EngraveResult(RunRecord Record, RunResult? Run, Exception? Error, RunLogFiles? Files, Exception? LogError)
{
    /// <summary>The state the session ended in.</summary>
    public RunState State => RunStateMachine.EndState(Record.Outcome);
}
